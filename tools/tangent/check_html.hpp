// SPDX-License-Identifier: MIT
// `tangent check --format html`: one self-contained page for people (a CI artefact).
#pragma once

#include <string>
#include <vector>

#include "tangent/check.hpp"

namespace tangent::cli {

// The report: the summary, every primitive with its findings, warnings and passed checks, and
// for each failing primitive a thumbnail of tangent-view's error view framed on its flagged
// triangles (a data: PNG) and a link that opens the file in the web viewer when the report
// sits beside a deployed build-web/. Nothing in it reaches the network. `reportPath` is where
// the page will be written ("-": standard output; links are then relative to the current
// directory). Without tangent-view or a display the page says why it has no thumbnails.
std::string htmlReport(const std::vector<gltf::FileCheck>& checks, const gltf::CheckOptions& options,
                       const std::string& reportPath);

}  // namespace tangent::cli
