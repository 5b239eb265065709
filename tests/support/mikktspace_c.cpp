// SPDX-License-Identifier: MIT
#include "support/mikktspace_c.hpp"

#include <mikktspace.h>

namespace tangent::testing {
namespace {

struct CallData {
  const MeshArrays* mesh;
  const FaceOrder* order;
  std::vector<ReferenceFrame>* frames;
};

const CallData& callData(const SMikkTSpaceContext* context) {
  return *static_cast<const CallData*>(context->m_pUserData);
}

// The original corner (index into mesh.indices) of face `face`, corner `vert` of the call.
std::size_t originalCorner(const CallData& data, int face, int vert) {
  const auto f = static_cast<std::size_t>(face);
  const auto k = static_cast<std::size_t>(vert);
  if (data.order->triangleOrder.empty()) return 3 * f + k;
  return 3 * std::size_t{data.order->triangleOrder[f]} + (k + data.order->cornerRotation[f]) % 3;
}

std::size_t vertexOf(const CallData& data, int face, int vert) {
  return data.mesh->indices[originalCorner(data, face, vert)];
}

int numFaces(const SMikkTSpaceContext* context) {
  return static_cast<int>(callData(context).mesh->indices.size() / 3);
}
int numVerticesOfFace(const SMikkTSpaceContext*, const int) {
  return 3;
}

void position(const SMikkTSpaceContext* context, float out[], const int face, const int vert) {
  const CallData& data = callData(context);
  const std::size_t v = vertexOf(data, face, vert);
  for (int i = 0; i < 3; ++i) out[i] = data.mesh->positions[3 * v + i];
}

void normal(const SMikkTSpaceContext* context, float out[], const int face, const int vert) {
  const CallData& data = callData(context);
  const std::size_t v = vertexOf(data, face, vert);
  for (int i = 0; i < 3; ++i) out[i] = data.mesh->normals[3 * v + i];
}

void texCoord(const SMikkTSpaceContext* context, float out[], const int face, const int vert) {
  const CallData& data = callData(context);
  const std::size_t v = vertexOf(data, face, vert);
  for (int i = 0; i < 2; ++i) out[i] = data.mesh->uvs[2 * v + i];
}

void setBasic(const SMikkTSpaceContext* context, const float tangent[], const float sign, const int face,
              const int vert) {
  const CallData& data = callData(context);
  ReferenceFrame& frame = (*data.frames)[originalCorner(data, face, vert)];
  for (int i = 0; i < 3; ++i) frame.tangent[i] = tangent[i];
  frame.sign = sign;
  frame.written = true;
}

void setFull(const SMikkTSpaceContext* context, const float tangent[], const float bitangent[], const float magnitudeS,
             const float magnitudeT, const tbool orientationPreserving, const int face, const int vert) {
  const CallData& data = callData(context);
  ReferenceFrame& frame = (*data.frames)[originalCorner(data, face, vert)];
  frame.initialSpace = tangent[0] == 1 && tangent[1] == 0 && tangent[2] == 0 && bitangent[0] == 0 &&
                       bitangent[1] == 1 && bitangent[2] == 0 && magnitudeS == 1 && magnitudeT == 1 &&
                       !orientationPreserving;
}

}  // namespace

std::vector<ReferenceFrame> referenceCornerFrames(const MeshArrays& mesh, const FaceOrder& order) {
  std::vector<ReferenceFrame> frames(mesh.indices.size());
  CallData data{&mesh, &order, &frames};
  SMikkTSpaceInterface callbacks{};
  callbacks.m_getNumFaces = numFaces;
  callbacks.m_getNumVerticesOfFace = numVerticesOfFace;
  callbacks.m_getPosition = position;
  callbacks.m_getNormal = normal;
  callbacks.m_getTexCoord = texCoord;
  callbacks.m_setTSpaceBasic = setBasic;
  callbacks.m_setTSpace = setFull;  // the reference calls both
  SMikkTSpaceContext context{};
  context.m_pInterface = &callbacks;
  context.m_pUserData = &data;
  if (!genTangSpaceDefault(&context)) return {};
  return frames;
}

}  // namespace tangent::testing
