// SPDX-License-Identifier: MIT
// The formats of `tangent check`'s report but HTML (check_html.hpp), one writer each over every
// file checked: text for people, JSON for tools (docs/check-json.md), JUnit XML for CI servers,
// GitHub workflow annotations, SARIF 2.1.0 for code-scanning tools, GitLab's code quality report.
#pragma once

#include <ostream>
#include <string>
#include <vector>

#include "tangent/check.hpp"

namespace tangent::cli {

// One run of the command: what JUnit's timestamps need.
struct RunTimes {
  std::vector<std::string> startedUtc;  // per file, ISO 8601
};

// Text for people.
void writeText(std::ostream& out, const std::vector<gltf::FileCheck>& checks);
// JSON for tools (docs/check-json.md).
void writeJson(std::ostream& out, const std::vector<gltf::FileCheck>& checks, const gltf::CheckOptions& options);
// JUnit XML: a suite per file, a test case per primitive and check.
void writeJunit(std::ostream& out, const std::vector<gltf::FileCheck>& checks, const RunTimes& times);
// GitHub Actions workflow commands (::error, ::warning), one per finding and warning.
void writeGithub(std::ostream& out, const std::vector<gltf::FileCheck>& checks);
// SARIF 2.1.0: a rule per check, a result per finding located at the file and the primitive.
void writeSarif(std::ostream& out, const std::vector<gltf::FileCheck>& checks, const gltf::CheckOptions& options);
// GitLab code quality (a subset of the Code Climate issue spec): a JSON array of issues.
void writeCodeClimate(std::ostream& out, const std::vector<gltf::FileCheck>& checks);

}  // namespace tangent::cli
