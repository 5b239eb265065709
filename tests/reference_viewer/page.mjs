// SPDX-License-Identifier: MIT
// The Khronos glTF Sample Viewer's engine (npm @khronosgroup/gltf-viewer) on a canvas, for
// khronos_compare_test.py: window.renderScene(url, exposure) loads a glTF (which carries its own
// camera and KHR_lights_punctual light), draws it with the punctual light only (no IBL, no tone
// mapping: its linear colour times the exposure, then its gamma 2.2) and answers the canvas as a
// PNG data URL. document.body.dataset.state is "ready" once the environment is loaded (the engine
// needs one even with IBL off), or "error: ..." when something failed.
import { GltfView, GltfState } from "@khronosgroup/gltf-viewer";

const canvas = document.getElementById("canvas");
const size = Number(new URLSearchParams(location.search).get("size") || 240);
canvas.width = canvas.height = size;
const gl = canvas.getContext("webgl2", { antialias: false, alpha: false, preserveDrawingBuffer: true });
const view = new GltfView(gl);
const loader = view.createResourceLoader(undefined, undefined, "./libs/");
const state = view.createState();
state.renderingParameters.useIBL = false;
state.renderingParameters.usePunctual = true;
state.renderingParameters.renderEnvironmentMap = false;
state.renderingParameters.toneMap = GltfState.ToneMaps.NONE;
// tangent-view's clear colour (41, 43, 48 in 8 bits), bluer than any pixel of these grey and red
// scenes: the tests tell the background by it.
state.renderingParameters.clearColor = [0.16, 0.17, 0.19, 1];

const nextFrame = () => new Promise((resolve) => requestAnimationFrame(resolve));

window.renderScene = async (url, exposure) => {
  state.gltf = await loader.loadGltf(url);
  state.sceneIndex = state.gltf.scene === undefined ? 0 : state.gltf.scene;
  state.cameraIndex = 0;
  state.renderingParameters.exposure = exposure;
  // The first frame compiles the shader variant and uploads what loading left; draw a second.
  for (let frame = 0; frame < 2; ++frame) {
    view.renderFrame(state, canvas.width, canvas.height);
    await nextFrame();
  }
  return canvas.toDataURL("image/png");
};

loader
  .loadEnvironment("environment.hdr", { lut_sheen_E_file: "lut_sheen_E.png" })
  .then((environment) => {
    state.environment = environment;
    document.body.dataset.state = "ready";
  })
  .catch((error) => {
    document.body.dataset.state = `error: ${error && error.stack ? error.stack : error}`;
  });
