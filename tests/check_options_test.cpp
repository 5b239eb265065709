// SPDX-License-Identifier: MIT
// `tangent check`'s per-check control (--only, --ignore, --tolerance CHECK=DEG,
// --allow-missing, --config) and its CI formats (github, sarif, junit), on a hand-made quad
// whose findings are known exactly; `-o -` and `bake --report -` write to standard output.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iterator>
#include <regex>

#include "support/run_command.hpp"
#include "support/skip_or_fail.hpp"
#include "support/temp_dir.hpp"
#include "support/test_assets.hpp"
#include "tangent/check.hpp"

namespace {

namespace fs = std::filesystem;
using Json = nlohmann::ordered_json;
using tangent::testing::runCommand;
using tangent::testing::TempDir;

std::string quoted(const fs::path& path) { return "'" + path.string() + "'"; }

// A unit quad in the XY plane, UVs with glTF's top-left origin, normal-mapped; the frame at
// every vertex is T = (1, 0, 0), w = +1 (w = -sign(UV area), and the UV area is negative).
// `tangents` (4 per vertex) replace that when given; `withTangent` false leaves TANGENT out;
// `normalLength` is the stored NORMAL's length.
fs::path writeQuad(const fs::path& dir, const std::string& name, std::vector<float> tangents = {}, bool withTangent = true,
                   float normalLength = 1) {
  fs::create_directories(dir);
  const std::vector<float> positions = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
  const float n = normalLength;
  const std::vector<float> normals = {0, 0, n, 0, 0, n, 0, 0, n, 0, 0, n};
  const std::vector<float> uvs = {0, 1, 1, 1, 1, 0, 0, 0};
  if (tangents.empty()) tangents = {1, 0, 0, 1, 1, 0, 0, 1, 1, 0, 0, 1, 1, 0, 0, 1};
  const std::vector<std::uint16_t> indices = {0, 1, 2, 0, 2, 3};
  std::vector<std::uint8_t> bin;
  auto append = [&](const void* data, std::size_t size) {
    const auto* bytes = static_cast<const std::uint8_t*>(data);
    bin.insert(bin.end(), bytes, bytes + size);
  };
  append(positions.data(), 48);
  append(normals.data(), 48);
  append(uvs.data(), 32);
  append(tangents.data(), 64);
  append(indices.data(), 12);
  Json attributes = {{"POSITION", 0}, {"NORMAL", 1}, {"TEXCOORD_0", 2}};
  if (withTangent) attributes["TANGENT"] = 3;
  const Json doc = {
      {"asset", {{"version", "2.0"}}},
      {"buffers", Json::array({{{"uri", name + ".bin"}, {"byteLength", bin.size()}}})},
      {"bufferViews", Json::array({{{"buffer", 0}, {"byteOffset", 0}, {"byteLength", 192}, {"target", 34962}},
                                   {{"buffer", 0}, {"byteOffset", 192}, {"byteLength", 12}, {"target", 34963}}})},
      {"accessors", Json::array({{{"bufferView", 0}, {"byteOffset", 0}, {"componentType", 5126}, {"count", 4}, {"type", "VEC3"},
                                  {"min", {0, 0, 0}}, {"max", {1, 1, 0}}},
                                 {{"bufferView", 0}, {"byteOffset", 48}, {"componentType", 5126}, {"count", 4}, {"type", "VEC3"}},
                                 {{"bufferView", 0}, {"byteOffset", 96}, {"componentType", 5126}, {"count", 4}, {"type", "VEC2"}},
                                 {{"bufferView", 0}, {"byteOffset", 128}, {"componentType", 5126}, {"count", 4}, {"type", "VEC4"}},
                                 {{"bufferView", 1}, {"componentType", 5123}, {"count", 6}, {"type", "SCALAR"}}})},
      {"materials", Json::array({{{"normalTexture", {{"index", 0}}}}})},
      {"textures", Json::array({{{"source", 0}}})},
      {"images", Json::array({{{"uri", "normal.png"}}})},
      {"meshes", Json::array({{{"primitives", Json::array({{{"attributes", attributes}, {"indices", 4}, {"material", 0}}})}}})},
      {"nodes", Json::array({{{"mesh", 0}}})},
      {"scenes", Json::array({{{"nodes", {0}}}})},
      {"scene", 0}};
  std::ofstream(dir / (name + ".bin"), std::ios::binary).write(reinterpret_cast<const char*>(bin.data()), static_cast<std::streamsize>(bin.size()));
  std::ofstream(dir / (name + ".gltf")) << doc.dump(2);
  return dir / (name + ".gltf");
}

// Vertex 2 twice too long: exactly one finding, `unit`, 1 of 4 vertices.
fs::path nonUnitQuad(const fs::path& dir) {
  return writeQuad(dir, "quad", {1, 0, 0, 1, 1, 0, 0, 1, 2, 0, 0, 1, 1, 0, 0, 1});
}

// Every tangent turned by `inPlane` degrees about the normal and tilted `outOfPlane` degrees
// towards it: still unit.
fs::path turnedQuad(const fs::path& dir, const std::string& name, double inPlane, double outOfPlane) {
  const double a = inPlane * M_PI / 180, b = outOfPlane * M_PI / 180;
  const float t[4] = {static_cast<float>(std::cos(a) * std::cos(b)), static_cast<float>(std::sin(a) * std::cos(b)),
                      static_cast<float>(std::sin(b)), 1};
  std::vector<float> tangents;
  for (int v = 0; v < 4; ++v) tangents.insert(tangents.end(), t, t + 4);
  return writeQuad(dir, name, tangents);
}

const std::string cli = TANGENT_CLI;

Json checkJson(const std::string& arguments) {
  const auto run = runCommand("(" + cli + " check --format json " + arguments + " 2>/dev/null)");
  try {
    return Json::parse(run.output);
  } catch (const std::exception& e) {
    ADD_FAILURE() << "not JSON (" << e.what() << "): " << run.output;
    return Json::object();
  }
}

std::vector<std::string> findingChecks(const Json& report) {
  std::vector<std::string> names;
  for (const auto& file : report["files"])
    for (const auto& p : file["primitives"])
      for (const auto& f : p["findings"]) names.push_back(f["check"].get<std::string>());
  return names;
}

TEST(CheckOptions, TheQuadIsCleanAndItsNonUnitTwinHasExactlyOneFinding) {
  TempDir dir;
  EXPECT_EQ(runCommand(cli + " check " + quoted(writeQuad(dir / "clean", "quad"))).exitCode, 0);
  const Json report = checkJson(quoted(nonUnitQuad(dir.path())));
  EXPECT_EQ(findingChecks(report), std::vector<std::string>{"unit"});
  const Json& finding = report["files"][0]["primitives"][0]["findings"][0];
  EXPECT_EQ(finding["failed"], 1);
  EXPECT_EQ(finding["total"], 4);
  EXPECT_EQ(finding["severityUnit"], "length");
  EXPECT_EQ(finding["limit"], 1e-3);
  EXPECT_EQ(finding["worst"][0]["severity"], 1.0);
  EXPECT_EQ(finding["worst"][0]["detail"], "vertex 2 |xyz| = 2 (2, 0, 0, w 1)");
}

TEST(CheckOptions, OnlyAndIgnore) {
  TempDir dir;
  const fs::path quad = nonUnitQuad(dir.path());
  const Json only = checkJson("--only unit,w " + quoted(quad));
  const Json& p = only["files"][0]["primitives"][0];
  EXPECT_EQ(findingChecks(only), std::vector<std::string>{"unit"});
  EXPECT_EQ(p["passed"], Json::array({"w"}));
  EXPECT_EQ(p["ignored"], Json::array({"present", "format", "finite", "w-uniform", "orthogonal", "handedness", "reference"}));
  EXPECT_EQ(only["settings"]["checks"], Json::array({"unit", "w"}));

  EXPECT_EQ(runCommand(cli + " check --ignore unit " + quoted(quad)).exitCode, 0);
  const Json ignored = checkJson("--ignore unit,reference " + quoted(quad));
  EXPECT_TRUE(findingChecks(ignored).empty());
  EXPECT_EQ(ignored["files"][0]["primitives"][0]["ignored"], Json::array({"unit", "reference"}));
  EXPECT_EQ(ignored["settings"]["ignored"], Json::array({"unit", "reference"}));
  EXPECT_EQ(runCommand(cli + " check --only " + quoted(quad)).exitCode, 2);
  EXPECT_EQ(runCommand(cli + " check --only units " + quoted(quad)).exitCode, 2);
  EXPECT_EQ(runCommand(cli + " check --ignore present,format,finite,unit,w,w-uniform,orthogonal,handedness,reference " + quoted(quad)).exitCode, 2);
}

TEST(CheckOptions, ToleranceForEachAngularCheck) {
  TempDir dir;
  const fs::path turned = turnedQuad(dir.path(), "turned", 5, 0);   // reference 5 deg off, in plane
  const fs::path tilted = turnedQuad(dir.path(), "tilted", 0, 3);   // 3 deg out of the plane
  EXPECT_EQ(findingChecks(checkJson(quoted(turned))), std::vector<std::string>{"reference"});
  EXPECT_TRUE(findingChecks(checkJson("--tolerance reference=6 " + quoted(turned))).empty());
  EXPECT_EQ(findingChecks(checkJson("--tolerance orthogonal=6 " + quoted(turned))), std::vector<std::string>{"reference"});
  EXPECT_EQ(findingChecks(checkJson(quoted(tilted))), (std::vector<std::string>{"orthogonal", "reference"}));
  EXPECT_EQ(findingChecks(checkJson("--tolerance orthogonal=4 " + quoted(tilted))), std::vector<std::string>{"reference"});
  EXPECT_TRUE(findingChecks(checkJson("--tolerance 4 " + quoted(tilted))).empty());
  const Json settings = checkJson("--tolerance orthogonal=4 " + quoted(tilted))["settings"];
  EXPECT_EQ(settings["tolerance"], (Json{{"orthogonal", 4.0}, {"reference", 1.0}}));
  EXPECT_EQ(runCommand(cli + " check --tolerance handedness=4 " + quoted(tilted)).exitCode, 2);
  EXPECT_EQ(runCommand(cli + " check --tolerance reference=0 " + quoted(tilted)).exitCode, 2);
}

TEST(CheckOptions, AllowMissing) {
  TempDir dir;
  const fs::path missing = writeQuad(dir.path(), "missing", {}, false);
  const auto failing = runCommand(cli + " check " + quoted(missing));
  EXPECT_EQ(failing.exitCode, 1);
  EXPECT_NE(failing.output.find("FAIL present"), std::string::npos) << failing.output;
  const auto allowed = runCommand(cli + " check --allow-missing " + quoted(missing));
  EXPECT_EQ(allowed.exitCode, 0) << allowed.output;
  EXPECT_NE(allowed.output.find("skipped mesh 0 primitive 0: no TANGENT, allowed (--allow-missing"), std::string::npos) << allowed.output;
  // A TANGENT that is present is still checked.
  EXPECT_EQ(runCommand(cli + " check --allow-missing " + quoted(nonUnitQuad(dir.path()))).exitCode, 1);
}

TEST(CheckOptions, ReferenceGeneratorByName) {
  TempDir dir;
  const fs::path quad = writeQuad(dir.path(), "quad");
  // A flat quad: every generator gives its frames, so each reference passes; the settings name it.
  for (const std::string name : {"mikktspace", "lengyel/angle", "lengyel/area", "lengyel/uniform", "flat"}) {
    const auto run = runCommand(cli + " check --format json --reference " + name + " " + quoted(quad));
    EXPECT_EQ(run.exitCode, 0) << name << ": " << run.output;
    EXPECT_EQ(Json::parse(run.output)["settings"]["reference"], name);
  }
  EXPECT_EQ(checkJson("--reference lengyel " + quoted(quad))["settings"]["reference"], "lengyel/angle");
  EXPECT_EQ(checkJson("--reference flat --method lengyel " + quoted(quad))["settings"]["reference"], "lengyel/angle");
  const auto bad = runCommand("(" + cli + " check --reference lengyel/volume " + quoted(quad) + " 2>&1)");
  EXPECT_EQ(bad.exitCode, 2);
  EXPECT_NE(bad.output.find("--reference: 'lengyel/volume' is not mikktspace, lengyel/angle"), std::string::npos) << bad.output;
  const fs::path config = dir / "tangent-check.json";
  std::ofstream(config) << R"({"reference": "lengyel/uniform"})";
  EXPECT_EQ(checkJson("--config " + quoted(config) + " " + quoted(quad))["settings"]["reference"], "lengyel/uniform");
  std::ofstream(config) << R"({"reference": "best"})";
  EXPECT_EQ(runCommand("(" + cli + " check --config " + quoted(config) + " " + quoted(quad) + " 2>/dev/null)").exitCode, 2);
}

TEST(CheckOptions, ConfigFileWithTheSameSettingsAndCommandLineOverrides) {
  TempDir dir;
  const fs::path turned = turnedQuad(dir.path(), "turned", 5, 0);
  const fs::path missing = writeQuad(dir.path(), "missing", {}, false);
  const fs::path config = dir / "tangent-check.json";
  std::ofstream(config) << R"({"tolerance": {"reference": 6}, "ignore": ["unit"], "allowMissing": true})";
  const Json report = checkJson("--config " + quoted(config) + " " + quoted(turned) + " " + quoted(missing));
  EXPECT_TRUE(findingChecks(report).empty());
  EXPECT_EQ(report["settings"]["config"], config.string());
  EXPECT_EQ(report["settings"]["tolerance"]["reference"], 6.0);
  EXPECT_EQ(report["settings"]["ignored"], Json::array({"unit"}));
  EXPECT_EQ(report["settings"]["allowMissing"], true);
  // The command line wins, wherever --config stands.
  EXPECT_EQ(findingChecks(checkJson(quoted(turned) + " --tolerance reference=2 --config " + quoted(config))),
            std::vector<std::string>{"reference"});
  for (const std::string bad : {R"({"ignore": ["units"]})", R"({"tolerance": {"w": 2}})", R"({"colour": 1})", "[1"}) {
    std::ofstream(dir / "bad.json") << bad;
    const auto run = runCommand(cli + " check --config " + quoted(dir / "bad.json") + " " + quoted(turned));
    EXPECT_EQ(run.exitCode, 2) << bad;
    EXPECT_NE(run.output.find("bad.json"), std::string::npos) << run.output;
  }
}

TEST(CheckFormats, GithubAnnotationsExactly) {
  TempDir dir;
  const fs::path quad = nonUnitQuad(dir.path());
  const auto run = runCommand(cli + " check --format github " + quoted(quad));
  EXPECT_EQ(run.exitCode, 1);
  EXPECT_EQ(run.output, "::error file=" + quad.string() + ",title=tangent check unit (mesh 0 primitive 0)::mesh 0 primitive 0: "
                        "1 of 4 vertices: |xyz| differs from 1 by more than 0.001 (float)%0Aworst: vertex 2 |xyz| = 2 (2, 0, 0, w 1)\n"
                        "::notice title=tangent check::1 file(s), 1 primitive(s) checked, 1 finding(s)\n");
  // Commas and colons in a file name are escaped in the property.
  const fs::path odd = dir / "a,b:c";
  fs::create_directories(odd);
  const fs::path oddQuad = nonUnitQuad(odd);
  const auto escaped = runCommand(cli + " check --format github " + quoted(oddQuad));
  EXPECT_EQ(escaped.output.rfind("::error file=" + dir.path().string() + "/a%2Cb%3Ac/quad.gltf,title=", 0), 0u) << escaped.output;
  const auto unreadable = runCommand("(" + cli + " check --format github " + quoted(dir / "none.glb") + " 2>/dev/null)");
  EXPECT_EQ(unreadable.exitCode, 2);
  EXPECT_EQ(unreadable.output.rfind("::error file=" + (dir / "none.glb").string() + ",title=tangent check%3A unreadable::", 0), 0u)
      << unreadable.output;
}

// SARIF 2.1.0: no schema validator or schema file is available offline here, so this asserts
// the schema's required properties (sarifLog: version, runs; run: tool; tool: driver;
// toolComponent: name; reportingDescriptor: id; result: message; message: text;
// invocation: executionSuccessful; notification: message) and the exact content.
TEST(CheckFormats, SarifStructureAndContent) {
  TempDir dir;
  const fs::path quad = nonUnitQuad(dir.path());
  const fs::path clean = writeQuad(dir / "clean dir", "clean");
  const auto run = runCommand("(" + cli + " check --format sarif -o - " + quoted(quad) + " " + quoted(clean) + " " + quoted(dir / "none.glb") + " 2>/dev/null)");
  EXPECT_EQ(run.exitCode, 2);  // one input unreadable
  const Json log = Json::parse(run.output);
  ASSERT_EQ(log["version"], "2.1.0");
  EXPECT_EQ(log["$schema"], "https://json.schemastore.org/sarif-2.1.0.json");
  ASSERT_EQ(log["runs"].size(), 1u);
  const Json& sarifRun = log["runs"][0];
  const Json& driver = sarifRun["tool"]["driver"];
  EXPECT_EQ(driver["name"], "tangent check");
  // A rule per check, then the one for warnings (CheckFormats.WarningsInEveryFormat).
  ASSERT_EQ(driver["rules"].size(), std::size(tangent::gltf::kCheckNames) + 1);
  EXPECT_EQ(driver["rules"].back()["defaultConfiguration"]["level"], "warning");
  for (std::size_t i = 0; i < std::size(tangent::gltf::kCheckNames); ++i) {
    EXPECT_EQ(driver["rules"][i]["id"], tangent::gltf::kCheckNames[i]);
    EXPECT_TRUE(driver["rules"][i]["shortDescription"]["text"].is_string());
  }
  ASSERT_EQ(sarifRun["results"].size(), 1u);
  const Json& result = sarifRun["results"][0];
  EXPECT_EQ(result["ruleId"], "unit");
  // SARIF 2.1.0 result.ruleIndex: "the index within the tool component rules array of the rule
  // object associated with this result", here tool.driver.rules.
  std::size_t unitRule = driver["rules"].size();
  for (std::size_t i = 0; i < driver["rules"].size(); ++i)
    if (driver["rules"][i]["id"] == "unit") unitRule = i;
  ASSERT_LT(unitRule, driver["rules"].size());
  EXPECT_EQ(result["ruleIndex"], unitRule);
  EXPECT_EQ(result["level"], "error");
  EXPECT_EQ(result["message"]["text"], "mesh 0 primitive 0: 1 of 4 vertices: |xyz| differs from 1 by more than 0.001 (float)");
  EXPECT_EQ(result["locations"][0]["physicalLocation"]["artifactLocation"]["uri"], quad.string());
  EXPECT_EQ(result["locations"][0]["logicalLocations"][0]["fullyQualifiedName"], "/meshes/0/primitives/0");
  EXPECT_EQ(result["properties"]["failed"], 1);
  const Json& invocation = sarifRun["invocations"][0];
  EXPECT_EQ(invocation["executionSuccessful"], false);
  ASSERT_EQ(invocation["toolExecutionNotifications"].size(), 1u);
  EXPECT_TRUE(invocation["toolExecutionNotifications"][0]["message"]["text"].is_string());
  EXPECT_EQ(invocation["toolExecutionNotifications"][0]["locations"][0]["physicalLocation"]["artifactLocation"]["uri"],
            (dir / "none.glb").string());
  EXPECT_EQ(invocation["properties"]["settings"]["method"], "mikktspace");
  // A path with a space is a percent-encoded URI reference.
  const auto spaced = Json::parse(runCommand(cli + " check --format sarif " + quoted(writeQuad(dir / "clean dir", "x", {2, 0, 0, 1, 1, 0, 0, 1, 1, 0, 0, 1, 1, 0, 0, 1}))).output);
  EXPECT_EQ(spaced["runs"][0]["results"][0]["locations"][0]["physicalLocation"]["artifactLocation"]["uri"],
            (dir.path() / "clean%20dir/x.gltf").string());
}

// The SARIF output against the SARIF 2.1.0 JSON schema itself (tests/node: the schema from
// Microsoft's SARIF multitool package, ajv with formats), with a broken copy as the control.
TEST(CheckFormats, SarifValidAgainstTheSchema) {
  const fs::path node = fs::path(TANGENT_SOURCE_DIR) / "tests/node";
  if (!fs::exists(node / "node_modules/@microsoft/sarif-multitool-linux/sarif-2.1.0.json") ||
      !fs::exists(node / "node_modules/ajv-formats"))
    TANGENT_SKIP_OR_FAIL("tests/node/node_modules lacks the SARIF schema or ajv: run `npm ci` in tests/node (scripts/test.sh does)");
  TempDir dir;
  const fs::path quad = nonUnitQuad(dir.path());
  const fs::path clean = writeQuad(dir / "clean dir", "clean");
  const fs::path log = dir / "check.sarif";
  EXPECT_EQ(runCommand(cli + " check --format sarif -o " + quoted(log) + " " + quoted(quad) + " " + quoted(clean) + " " +
                       quoted(dir / "none.glb"))
                .exitCode,
            2);
  Json broken = Json::parse(std::ifstream(log));
  ASSERT_EQ(broken["runs"][0]["results"].size(), 1u);  // a finding and a notification are in what is validated
  broken["runs"][0]["tool"].erase("driver");
  std::ofstream(dir / "broken.sarif") << broken.dump();
  const std::string validate = "node " + quoted(node / "validate_sarif.mjs") + " ";
  const auto valid = runCommand(validate + quoted(log));
  EXPECT_EQ(valid.exitCode, 0) << valid.output;
  const auto invalid = runCommand(validate + quoted(dir / "broken.sarif"));
  EXPECT_EQ(invalid.exitCode, 1) << invalid.output;
  EXPECT_NE(invalid.output.find("must have required property 'driver'"), std::string::npos) << invalid.output;
}

TEST(CheckFormats, JunitHasTimeTimestampFileAndSkipped) {
  TempDir dir;
  const fs::path quad = nonUnitQuad(dir.path());
  const fs::path missing = writeQuad(dir.path(), "missing", {}, false);
  const fs::path report = dir / "report.xml";
  EXPECT_EQ(runCommand(cli + " check --format junit -o " + quoted(report) + " " + quoted(quad) + " " + quoted(missing)).exitCode, 1);
  const std::string script = R"(import sys, re, xml.etree.ElementTree as ET
root = ET.parse(sys.argv[1]).getroot()
print(root.tag, root.get('tests'), root.get('failures'), root.get('errors'), root.get('skipped'), float(root.get('time')) >= 0)
for suite in root.findall('testsuite'):
    assert re.fullmatch(r'\d{4}-\d\d-\d\dT\d\d:\d\d:\d\d', suite.get('timestamp')), suite.get('timestamp')
    assert float(suite.get('time')) >= 0
    print(suite.get('name') == suite.get('file'), suite.get('tests'), suite.get('failures'), suite.get('skipped'))
    # In the order docs/check.md lists the checks (argv[2]): the JUnit format fixes no order of
    # test cases, and the writer lists passes before failures.
    order = sys.argv[2].split(',')
    for case in sorted(suite.findall('testcase'), key=lambda case: order.index(case.get('name'))):
        assert case.get('file') == suite.get('file')
        state = 'failure' if case.find('failure') is not None else 'skipped' if case.find('skipped') is not None else 'ok'
        print(' ', case.get('name'), state)
)";
  // Valid against the JUnit XML schema (tests/schemas/junit.xsd, xmllint); the control lacks a
  // testcase's required name.
  const std::string schema = quoted(fs::path(TANGENT_SOURCE_DIR) / "tests/schemas/junit.xsd");
  const auto valid = runCommand("xmllint --noout --schema " + schema + " " + quoted(report));
  EXPECT_EQ(valid.exitCode, 0) << valid.output;
  std::ifstream xml(report);
  std::string text((std::istreambuf_iterator<char>(xml)), std::istreambuf_iterator<char>());
  const std::size_t named = text.find("name=\"present\"");
  ASSERT_NE(named, std::string::npos);
  std::ofstream(dir / "broken.xml") << text.erase(named, std::string("name=\"present\"").size());
  const auto invalid = runCommand("xmllint --noout --schema " + schema + " " + quoted(dir / "broken.xml"));
  EXPECT_NE(invalid.exitCode, 0);
  EXPECT_NE(invalid.output.find("The attribute 'name' is required but missing"), std::string::npos) << invalid.output;
  std::ofstream(dir / "read.py") << script;
  // The checks in the order docs/check.md lists them (kCheckNames follows it).
  const std::vector<std::string> documentedOrder = {"present",   "format",     "finite",     "unit",     "w",
                                                    "w-uniform", "orthogonal", "handedness", "reference"};
  ASSERT_TRUE(std::equal(documentedOrder.begin(), documentedOrder.end(), std::begin(tangent::gltf::kCheckNames),
                         std::end(tangent::gltf::kCheckNames)));
  std::string orderArgument;
  for (const auto& name : documentedOrder) orderArgument += (orderArgument.empty() ? "" : ",") + name;
  const auto parsed = runCommand("/usr/bin/python3 " + quoted(dir / "read.py") + " " + quoted(report) + " " + orderArgument);
  ASSERT_EQ(parsed.exitCode, 0) << parsed.output;
  // A case per check and file. The non-unit quad: every check passes but unit (vertex 2 is
  // twice too long). The quad without TANGENT: present fails and gates the rest, skipped.
  const std::size_t checks = documentedOrder.size();
  std::string expected = "testsuites " + std::to_string(2 * checks) + " 2 0 " + std::to_string(checks - 1) + " True\n";
  expected += "True " + std::to_string(checks) + " 1 0\n";
  for (const auto& name : documentedOrder) expected += "  " + name + (name == "unit" ? " failure\n" : " ok\n");
  expected += "True " + std::to_string(checks) + " 1 " + std::to_string(checks - 1) + "\n";
  for (const auto& name : documentedOrder) expected += "  " + name + (name == "present" ? " failure\n" : " skipped\n");
  EXPECT_EQ(parsed.output, expected);
}

// A warning (here: NORMAL stored at half length, which readers normalize; docs/check.md) is
// not a failure, and every report format carries it: text WARN, JSON `warnings`, a GitHub
// ::warning annotation, a SARIF result of level "warning" (valid against the schema), and the
// JUnit suite's <system-out> (valid against tests/schemas/junit.xsd).
TEST(CheckFormats, WarningsInEveryFormat) {
  TempDir dir;
  const fs::path quad = writeQuad(dir.path(), "short-normals", {}, true, 0.5f);
  const std::string warning = "NORMAL is not unit length: worst 0.5, beyond the 5e-05 of float rounding; 4 normals normalized first, as glTF readers do";

  const auto text = runCommand(cli + " check " + quoted(quad));
  EXPECT_EQ(text.exitCode, 0) << text.output;
  EXPECT_NE(text.output.find("    WARN " + warning + "\n"), std::string::npos) << text.output;

  const Json json = checkJson(quoted(quad));
  const Json& primitive = json["files"][0]["primitives"][0];
  EXPECT_TRUE(primitive["findings"].empty());
  EXPECT_EQ(primitive["warnings"], Json::array({warning}));

  const auto github = runCommand(cli + " check --format github " + quoted(quad));
  EXPECT_EQ(github.exitCode, 0);
  EXPECT_EQ(github.output, "::warning file=" + quad.string() + ",title=tangent check (mesh 0 primitive 0)::" + warning + "\n"
                           "::notice title=tangent check::1 file(s), 1 primitive(s) checked, 0 finding(s)\n");

  const fs::path sarifPath = dir / "check.sarif";
  EXPECT_EQ(runCommand(cli + " check --format sarif -o " + quoted(sarifPath) + " " + quoted(quad)).exitCode, 0);
  const Json sarif = Json::parse(std::ifstream(sarifPath));
  const Json& sarifRun = sarif["runs"][0];
  ASSERT_EQ(sarifRun["results"].size(), 1u);
  const Json& result = sarifRun["results"][0];
  EXPECT_EQ(result["level"], "warning");
  EXPECT_EQ(result["message"]["text"], "mesh 0 primitive 0: " + warning);
  EXPECT_EQ(result["locations"][0]["logicalLocations"][0]["fullyQualifiedName"], "/meshes/0/primitives/0");
  const Json& rule = sarifRun["tool"]["driver"]["rules"][result["ruleIndex"].get<std::size_t>()];
  EXPECT_EQ(rule["id"], result["ruleId"]);
  EXPECT_EQ(rule["defaultConfiguration"]["level"], "warning");

  const fs::path junitPath = dir / "report.xml";
  EXPECT_EQ(runCommand(cli + " check --format junit -o " + quoted(junitPath) + " " + quoted(quad)).exitCode, 0);
  const std::string schema = quoted(fs::path(TANGENT_SOURCE_DIR) / "tests/schemas/junit.xsd");
  const auto valid = runCommand("xmllint --noout --schema " + schema + " " + quoted(junitPath));
  EXPECT_EQ(valid.exitCode, 0) << valid.output;
  const auto systemOut = runCommand("/usr/bin/python3 -c \"import sys, xml.etree.ElementTree as ET; "
                                    "suite = ET.parse(sys.argv[1]).getroot().find('testsuite'); "
                                    "print(suite.get('failures'), suite.find('system-out').text, end='')\" " + quoted(junitPath));
  EXPECT_EQ(systemOut.output, "0 WARN mesh 0 primitive 0: " + warning + "\n");

  const fs::path node = fs::path(TANGENT_SOURCE_DIR) / "tests/node";
  if (!fs::exists(node / "node_modules/@microsoft/sarif-multitool-linux/sarif-2.1.0.json") || !fs::exists(node / "node_modules/ajv-formats"))
    TANGENT_SKIP_OR_FAIL("tests/node/node_modules lacks the SARIF schema or ajv: run `npm ci` in tests/node (scripts/test.sh does)");
  const auto validated = runCommand("node " + quoted(node / "validate_sarif.mjs") + " " + quoted(sarifPath));
  EXPECT_EQ(validated.exitCode, 0) << validated.output;
}

// --min-coverage (issue 37): after gltfpack -vt 8, 8-bit UVs leave the UV orientation of most
// small triangles undecided (a 128 x 128 UV sphere's, NormalTangentTest's), so `reference`
// compares a few percent of the corners or none; check then warns (exit code 0) in every
// format, with the compared count and total as the JSON counts give them. The same bake without
// the pipeline gets no such warning, and --min-coverage 0 (or "minCoverage": 0 in the config
// file) turns it off.
TEST(CheckOptions, MinCoverageWarnsWhereRoundingLeavesMostCornersUncompared) {
  if (runCommand("command -v gltfpack").exitCode != 0)
    TANGENT_SKIP_OR_FAIL("gltfpack is not installed (scripts/install-deps.sh): the coverage warning was not tested");
  TempDir dir;
  std::vector<fs::path> sources = {
      tangent::testing::writeAsset(tangent::testing::meshAsset("sphere", tangent::testing::makeSphere(128, 128)), dir / "in", true)};
  const fs::path shared = tangent::testing::sharedAssets();
  if (!shared.empty()) sources.push_back(shared / "NormalTangentTest.glb");
  for (const fs::path& source : sources) {
    SCOPED_TRACE(source.string());
    const fs::path baked = dir / (source.stem().string() + "-baked.glb"), packed = dir / (source.stem().string() + "-vt8.glb");
    ASSERT_EQ(runCommand(cli + " bake " + quoted(source) + " -o " + quoted(baked) + " --quiet").exitCode, 0);
    const auto pack = runCommand("gltfpack -i " + quoted(baked) + " -o " + quoted(packed) + " -vt 8");
    ASSERT_EQ(pack.exitCode, 0) << pack.output;

    // The coverage warnings of a report's primitives, and the ones its counts call for.
    auto coverageWarnings = [](const Json& report) {
      std::vector<std::string> found;
      for (const auto& p : report["files"][0]["primitives"])
        for (const auto& w : p["warnings"])
          if (w.get<std::string>().find(" compared only ") != std::string::npos) found.push_back(w.get<std::string>());
      return found;
    };
    auto expectedReferenceWarnings = [](const Json& report, double minCoverage) {
      std::vector<std::string> expected;
      for (const auto& p : report["files"][0]["primitives"]) {
        const std::uint64_t total = 3 * p["triangles"].get<std::uint64_t>();
        const std::uint64_t compared =
            total - p["referenceUnresolvedCorners"].get<std::uint64_t>() - p["referenceUndefinedCorners"].get<std::uint64_t>();
        if (double(compared) < minCoverage * double(total))
          expected.push_back("reference compared only " + std::to_string(compared) + " of " + std::to_string(total) + " corners (");
      }
      return expected;
    };

    const Json report = checkJson(quoted(packed));
    EXPECT_EQ(report["settings"]["minCoverage"], 0.5);
    const std::vector<std::string> expected = expectedReferenceWarnings(report, 0.5);
    ASSERT_FALSE(expected.empty()) << "gltfpack -vt 8 no longer leaves most corners uncompared: " << report.dump(1);
    std::vector<std::string> warnings = coverageWarnings(report);
    for (const std::string& start : expected) {
      const auto it = std::find_if(warnings.begin(), warnings.end(), [&](const std::string& w) { return w.rfind(start, 0) == 0; });
      ASSERT_NE(it, warnings.end()) << start << " missing: " << report.dump(1);
      // Why: the rounding's count, as JSON has it.
      const std::string unresolved = std::to_string(report["files"][0]["primitives"][0]["referenceUnresolvedCorners"].get<std::uint64_t>());
      EXPECT_NE(it->find(": " + unresolved + " whose frame or UV orientation rounded positions/UVs leave undecided"), std::string::npos) << *it;
    }
    // Any handedness warning agrees with JSON's undecided count and the triangle total.
    for (const std::string& w : warnings) {
      if (w.rfind("handedness", 0) != 0) continue;
      unsigned long long compared = 0, total = 0, undecided = 0;
      ASSERT_EQ(std::sscanf(w.c_str(), "handedness compared only %llu of %llu triangles", &compared, &total), 2) << w;
      ASSERT_EQ(std::sscanf(w.substr(w.find("): ") + 3).c_str(), "%llu", &undecided), 1) << w;
      const Json& p = report["files"][0]["primitives"][0];
      EXPECT_EQ(total, p["triangles"].get<std::uint64_t>());
      EXPECT_EQ(undecided, p["handednessUndecidedTriangles"].get<std::uint64_t>());
      EXPECT_LT(double(compared), 0.5 * double(total));
    }
    const std::string first = warnings.at(0);

    // Every format, exit code 0.
    const auto text = runCommand(cli + " check " + quoted(packed));
    EXPECT_EQ(text.exitCode, 0) << text.output;
    EXPECT_NE(text.output.find("    WARN " + first + "\n"), std::string::npos) << text.output;
    const auto github = runCommand(cli + " check --format github " + quoted(packed));
    EXPECT_EQ(github.exitCode, 0);
    // GitHub's data escapes % as %25.
    std::string githubFirst = first;
    githubFirst.replace(githubFirst.find("%,"), 2, "%25,");
    EXPECT_NE(github.output.find(",title=tangent check (mesh 0 primitive 0)::" + githubFirst + "\n"), std::string::npos) << github.output;
    const auto sarif = runCommand(cli + " check --format sarif " + quoted(packed));
    EXPECT_EQ(sarif.exitCode, 0);
    bool inSarif = false;
    const Json sarifLog = Json::parse(sarif.output);
    for (const auto& result : sarifLog["runs"][0]["results"])
      inSarif = inSarif || (result["level"] == "warning" && result["message"]["text"] == "mesh 0 primitive 0: " + first);
    EXPECT_TRUE(inSarif) << sarif.output;
    const auto junit = runCommand(cli + " check --format junit " + quoted(packed));
    EXPECT_EQ(junit.exitCode, 0);
    EXPECT_NE(junit.output.find("WARN mesh 0 primitive 0: " + first), std::string::npos) << junit.output;
    const auto html = runCommand("TANGENT_VIEW= " + cli + " check --format html -o - " + quoted(packed));
    EXPECT_EQ(html.exitCode, 0);
    EXPECT_NE(html.output.find("<p>warning: " + first.substr(0, first.find(" ("))), std::string::npos);

    // Off: on the command line and in the config file; the baked file warns of nothing.
    EXPECT_TRUE(coverageWarnings(checkJson("--min-coverage 0 " + quoted(packed))).empty());
    const fs::path config = dir / (source.stem().string() + "-check.json");
    std::ofstream(config) << R"({"minCoverage": 0})";
    EXPECT_TRUE(coverageWarnings(checkJson("--config " + quoted(config) + " " + quoted(packed))).empty());
    EXPECT_EQ(runCommand(cli + " check --min-coverage 0 " + quoted(packed)).exitCode, 0);
    const Json clean = checkJson(quoted(baked));
    EXPECT_TRUE(expectedReferenceWarnings(clean, 0.5).empty()) << clean.dump(1);
    EXPECT_TRUE(coverageWarnings(clean).empty()) << clean.dump(1);
    // At 1 any uncompared corner is worth a warning.
    EXPECT_GE(coverageWarnings(checkJson("--min-coverage 1 " + quoted(packed))).size(), expected.size());

    for (const std::string bad : {"1.5", "-0.1", "half", "", "nan"})
      EXPECT_EQ(runCommand("(" + cli + " check --min-coverage '" + bad + "' " + quoted(packed) + " 2>/dev/null)").exitCode, 2) << bad;
    std::ofstream(config) << R"({"minCoverage": 2})";
    EXPECT_EQ(runCommand("(" + cli + " check --config " + quoted(config) + " " + quoted(packed) + " 2>/dev/null)").exitCode, 2);
  }
  if (shared.empty()) TANGENT_SKIP_OR_FAIL("../shared/assets is absent: only the generated sphere went through gltfpack -vt 8");
}

// --identify's generator per primitive in SARIF (the run's property bag, schema-valid) and JUnit
// (suite properties, valid against tests/schemas/junit.xsd), as in JSON.
TEST(CheckFormats, IdentifiedGeneratorInSarifAndJunit) {
  TempDir dir;
  const fs::path quad = writeQuad(dir.path(), "quad");
  const std::string generator = checkJson("--identify " + quoted(quad))["files"][0]["primitives"][0]["generator"];
  EXPECT_FALSE(generator.empty());
  const fs::path sarifPath = dir / "check.sarif";
  EXPECT_EQ(runCommand(cli + " check --identify --format sarif -o " + quoted(sarifPath) + " " + quoted(quad)).exitCode, 0);
  const Json sarif = Json::parse(std::ifstream(sarifPath));
  const Json& entry = sarif["runs"][0]["properties"]["generators"][0];
  EXPECT_EQ(entry["generator"], generator);
  EXPECT_EQ(entry["primitive"], "/meshes/0/primitives/0");
  EXPECT_EQ(entry["uri"], quad.string());
  const fs::path junitPath = dir / "report.xml";
  EXPECT_EQ(runCommand(cli + " check --identify --format junit -o " + quoted(junitPath) + " " + quoted(quad)).exitCode, 0);
  const auto valid = runCommand("xmllint --noout --schema " + quoted(fs::path(TANGENT_SOURCE_DIR) / "tests/schemas/junit.xsd") + " " +
                                quoted(junitPath));
  EXPECT_EQ(valid.exitCode, 0) << valid.output;
  const auto property = runCommand("/usr/bin/python3 -c \"import sys, xml.etree.ElementTree as ET; "
                                   "p = ET.parse(sys.argv[1]).getroot().find('testsuite/properties/property'); "
                                   "print(p.get('name'), '=', p.get('value'), end='')\" " + quoted(junitPath));
  EXPECT_EQ(property.output, "generator mesh 0 primitive 0 = " + generator);
  // Without --identify neither carries it.
  const auto plain = Json::parse(runCommand(cli + " check --format sarif " + quoted(quad)).output);
  EXPECT_FALSE(plain["runs"][0].contains("properties"));
  const fs::path node = fs::path(TANGENT_SOURCE_DIR) / "tests/node";
  if (!fs::exists(node / "node_modules/@microsoft/sarif-multitool-linux/sarif-2.1.0.json") || !fs::exists(node / "node_modules/ajv-formats"))
    TANGENT_SKIP_OR_FAIL("tests/node/node_modules lacks the SARIF schema or ajv: run `npm ci` in tests/node (scripts/test.sh does)");
  const auto validated = runCommand("node " + quoted(node / "validate_sarif.mjs") + " " + quoted(sarifPath));
  EXPECT_EQ(validated.exitCode, 0) << validated.output;
}

TEST(CheckFormats, DashWritesToStandardOutput) {
  TempDir dir;
  const fs::path quad = nonUnitQuad(dir.path());
  const auto json = runCommand("(" + cli + " check --format json -o - " + quoted(quad) + " 2>/dev/null)");
  EXPECT_EQ(json.exitCode, 1);
  EXPECT_EQ(Json::parse(json.output)["schema"], "libtangent-check/2");
  EXPECT_FALSE(fs::exists("-"));
  // bake --report -: the report on stdout, the human-readable lines on stderr.
  const auto bake = runCommand("(" + cli + " bake " + quoted(quad) + " -o " + quoted(dir / "out.glb") + " --report - 2>/dev/null)");
  ASSERT_EQ(bake.exitCode, 0) << bake.output;
  const Json report = Json::parse(bake.output);
  EXPECT_EQ(report[0]["primitives"][0]["action"], "baked");
  EXPECT_EQ(report[0]["primitives"][0]["failedChecks"], Json::array({"unit"}));
  EXPECT_EQ(report[0]["primitives"][0]["reason"], "existing TANGENT fails tangent check (unit: 1 of 4 vertices); recomputed");
}

// bake -o -: the .glb goes to stdout, byte for byte what -o FILE writes; messages go to
// stderr; external images are embedded, and one that cannot be (no mimeType, bytes of no known
// image type) is refused naming it; with --keep-external an asset with external images is
// refused (a stream cannot carry them) and leaves nothing behind.
TEST(BakeOutput, DashWritesTheGlbToStandardOutput) {
  TempDir dir;
  std::ofstream(dir / "quad.obj") << "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nvn 0 0 1\n"
                                     "f 1/1/1 2/2/1 3/3/1\nf 1/1/1 3/3/1 4/4/1\n";
  const auto file = runCommand(cli + " bake " + quoted(dir / "quad.obj") + " -o " + quoted(dir / "file.glb") + " --quiet");
  ASSERT_EQ(file.exitCode, 0) << file.output;
  const auto streamed = runCommand("(" + cli + " bake " + quoted(dir / "quad.obj") + " -o - 2>" + quoted(dir / "stderr.txt") + ")");
  ASSERT_EQ(streamed.exitCode, 0) << streamed.output;
  std::ifstream in(dir / "file.glb", std::ios::binary);
  const std::string written((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_GT(written.size(), 12u);
  EXPECT_EQ(streamed.output, written);
  std::ifstream log(dir / "stderr.txt");
  const std::string messages((std::istreambuf_iterator<char>(log)), std::istreambuf_iterator<char>());
  EXPECT_NE(messages.find("quad.obj -> -: 1 baked"), std::string::npos) << messages;
  EXPECT_FALSE(fs::exists("-"));

  const fs::path quad = writeQuad(dir.path(), "quad");  // refers to normal.png
  std::ofstream(dir / "normal.png") << "not read";
  const auto unknown = runCommand("(" + cli + " bake " + quoted(quad) + " -o - 2>&1 >/dev/null)");
  EXPECT_EQ(unknown.exitCode, 1);
  EXPECT_NE(unknown.output.find("quad.gltf: /images/0: has no mimeType and its bytes are not PNG, JPEG, WebP or KTX2"),
            std::string::npos)
      << unknown.output;
  const auto refused = runCommand("(" + cli + " bake " + quoted(quad) + " -o - --keep-external 2>&1 >/dev/null)");
  EXPECT_EQ(refused.exitCode, 1);
  EXPECT_NE(refused.output.find("quad.gltf: -o - writes one .glb, but the asset refers to external files (normal.png)"),
            std::string::npos)
      << refused.output;
  const auto both = runCommand(cli + " bake " + quoted(quad) + " -o - --report -");
  EXPECT_EQ(both.exitCode, 2);
  EXPECT_NE(both.output.find("cannot both write to standard output"), std::string::npos) << both.output;
}

}  // namespace
