// SPDX-License-Identifier: MIT
#include "peers.hpp"

#include <stdexcept>

#ifdef TANGENT_BENCH_PEERS
#include "meshoptimizer.h"
#include "mikktspace.h"
#endif

namespace tangent::bench {

std::string_view toString(Peer peer) {
  switch (peer) {
    case Peer::referenceMikktspace:
      return "mikktspace.c";
    case Peer::meshoptCompatible:
      return "meshopt/compatible";
    case Peer::meshoptDefault:
      return "meshopt/default";
  }
  return "?";
}

#ifdef TANGENT_BENCH_PEERS

namespace {

// The reference reads the mesh through callbacks, one face and corner at a time.
struct MikkUserData {
  const MeshArrays* mesh;
  float* cornerTangents;
};

const MikkUserData& user(const SMikkTSpaceContext* context) {
  return *static_cast<const MikkUserData*>(context->m_pUserData);
}
std::uint32_t vertexOf(const SMikkTSpaceContext* context, int face, int corner) {
  return user(context).mesh->indices[3 * static_cast<std::size_t>(face) + corner];
}

int mikkFaces(const SMikkTSpaceContext* context) {
  return static_cast<int>(user(context).mesh->indices.size() / 3);
}
int mikkVerticesOfFace(const SMikkTSpaceContext*, const int) {
  return 3;
}
void mikkPosition(const SMikkTSpaceContext* context, float out[], const int face, const int corner) {
  const float* p = &user(context).mesh->positions[3 * static_cast<std::size_t>(vertexOf(context, face, corner))];
  out[0] = p[0], out[1] = p[1], out[2] = p[2];
}
void mikkNormal(const SMikkTSpaceContext* context, float out[], const int face, const int corner) {
  const float* n = &user(context).mesh->normals[3 * static_cast<std::size_t>(vertexOf(context, face, corner))];
  out[0] = n[0], out[1] = n[1], out[2] = n[2];
}
void mikkTexCoord(const SMikkTSpaceContext* context, float out[], const int face, const int corner) {
  const float* uv = &user(context).mesh->uvs[2 * static_cast<std::size_t>(vertexOf(context, face, corner))];
  out[0] = uv[0], out[1] = uv[1];
}
void mikkSetTangent(const SMikkTSpaceContext* context, const float tangent[], const float sign, const int face,
                    const int corner) {
  float* out = &user(context).cornerTangents[4 * (3 * static_cast<std::size_t>(face) + corner)];
  out[0] = tangent[0], out[1] = tangent[1], out[2] = tangent[2], out[3] = sign;
}

void referenceMikktspace(const MeshArrays& mesh, std::span<float> cornerTangents) {
  SMikkTSpaceInterface callbacks{};
  callbacks.m_getNumFaces = mikkFaces;
  callbacks.m_getNumVerticesOfFace = mikkVerticesOfFace;
  callbacks.m_getPosition = mikkPosition;
  callbacks.m_getNormal = mikkNormal;
  callbacks.m_getTexCoord = mikkTexCoord;
  callbacks.m_setTSpaceBasic = mikkSetTangent;
  MikkUserData data{&mesh, cornerTangents.data()};
  SMikkTSpaceContext context{&callbacks, &data};
  if (!genTangSpaceDefault(&context))
    throw std::runtime_error("mikktspace.c: genTangSpaceDefault failed (out of memory)");
}

}  // namespace

const std::vector<Peer>& peers() {
  static const std::vector<Peer> all = {Peer::referenceMikktspace, Peer::meshoptCompatible, Peer::meshoptDefault};
  return all;
}

std::string peersNote() {
  return "peers compiled from " TANGENT_BENCH_PEERS_DIR;
}

void runPeer(Peer peer, const MeshArrays& mesh, std::span<float> cornerTangents) {
  if (cornerTangents.size() != mesh.indices.size() * 4)
    throw std::invalid_argument("runPeer: 4 floats per corner expected");
  if (peer == Peer::referenceMikktspace) return referenceMikktspace(mesh, cornerTangents);
  // Indexed input, one index per corner; one xyzw per corner out.
  meshopt_generateTangents(cornerTangents.data(), mesh.indices.data(), mesh.indices.size(), mesh.positions.data(),
                           mesh.positions.size() / 3, 3 * sizeof(float), mesh.normals.data(), 3 * sizeof(float),
                           mesh.uvs.data(), 2 * sizeof(float),
                           peer == Peer::meshoptCompatible ? unsigned(meshopt_TangentCompatible) : 0u);
}

#else

const std::vector<Peer>& peers() {
  static const std::vector<Peer> none;
  return none;
}

std::string peersNote() {
  return "peers left out: ../shared/peers (mikktspace.c, meshoptimizer) was not found when this build was configured";
}

void runPeer(Peer, const MeshArrays&, std::span<float>) {
  throw std::logic_error("built without the peers");
}

#endif

}  // namespace tangent::bench
