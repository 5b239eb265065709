// SPDX-License-Identifier: MIT
// The report formats of `tangent check` (check_formats.hpp).
#include "check_formats.hpp"

#include <algorithm>
#include <bitset>
#include <cctype>
#include <fstream>
#include <map>
#include <optional>
#include <set>
#include <sstream>

#include "check_names.hpp"
#include "commands.hpp"
#include "tangent/digest.hpp"
#include "tangent/text.hpp"

namespace tangent::cli {
namespace {

// XML 1.0 text: the markup characters as entities, control characters XML forbids as a space,
// bytes that are not UTF-8 as \xHH (the document declares UTF-8).
std::string xmlEscape(const std::string& raw) {
  std::string out;
  for (char c : text::utf8Safe(raw)) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&apos;"; break;
      default:
        if (static_cast<unsigned char>(c) < 0x20 && c != '\n' && c != '\t') out += ' ';
        else out += c;
    }
  }
  return out;
}

}  // namespace

void writeText(std::ostream& out, const std::vector<gltf::FileCheck>& checks) {
  std::size_t primitives = 0, findings = 0, errors = 0;
  for (const auto& file : checks) {
    out << shown(file.file) << "\n";
    if (!file.error.empty()) {
      ++errors;
      out << "  ERROR " << shown(file.error) << "\n";
      continue;
    }
    for (const auto& p : file.primitives) {
      ++primitives;
      out << "  " << primitiveName(p) << " (TEXCOORD_" << p.texCoord << ", " << p.vertices << " vertices, " << p.triangles
          << " triangles): " << (p.findings.empty() ? "ok" : std::to_string(p.findings.size()) + " finding(s)") << "\n";
      for (const auto& f : p.findings) {
        ++findings;
        out << "    FAIL " << f.check << ": " << shown(findingSummary(f)) << "\n";
        for (const auto& s : f.worst) out << "         " << shown(s.detail) << "\n";
      }
      if (!p.passed.empty()) {
        out << "    ok  ";
        for (const auto& name : p.passed) out << " " << name;
        out << "\n";
      }
      if (!p.notRun.empty()) {
        out << "    not run:";
        for (const auto& name : p.notRun) out << " " << name;
        out << "\n";
      }
      if (!p.ignored.empty()) {
        out << "    ignored:";
        for (const auto& name : p.ignored) out << " " << name;
        out << "\n";
      }
      for (const auto& warning : p.warnings) out << "    WARN " << shown(warning) << "\n";
      if (!p.generator.empty()) {
        out << "    generator: " << shown(p.generator);
        for (const auto& g : p.generators) {
          char line[160];
          std::snprintf(line, sizeof line, "%s %s median %.3g max %.3g deg, w %.1f%%", &g == &p.generators.front() ? " (" : ";",
                        g.name.c_str(), g.medianDegrees, g.maxDegrees, 100 * g.wAgreement);
          out << line;
        }
        out << ")\n";
      }
      if (p.referenceUnresolved)
        out << "    (" << p.referenceUnresolved << " corners have a frame their rounded positions/UVs leave open; not compared)\n";
      if (p.handednessUndecided || p.referenceWUndecided)
        out << "    (" << p.handednessUndecided << " triangles have a UV orientation their rounded positions/UVs leave open: handedness "
            << "skips them, reference compares the angle but not w at the " << p.referenceWUndecided << " of their corners where w agrees)\n";
      if (p.referenceUndefined) out << "    (" << p.referenceUndefined << " corners have no defined reference frame; not compared)\n";
    }
    for (const auto& s : file.skipped) out << "  skipped " << shown(s) << "\n";
  }
  out << checks.size() << " file(s), " << primitives << " primitive(s) checked, " << findings << " finding(s)"
      << (errors ? ", " + std::to_string(errors) + " unreadable" : "") << "\n";
}

void writeJson(std::ostream& out, const std::vector<gltf::FileCheck>& checks, const gltf::CheckOptions& options) {
  nlohmann::ordered_json files = nlohmann::ordered_json::array();
  std::size_t findings = 0, errors = 0, primitives = 0;
  for (const auto& file : checks) {
    files.push_back(gltf::toJson(file));
    errors += !file.error.empty();
    primitives += file.primitives.size();
    for (const auto& p : file.primitives) findings += p.findings.size();
  }
  nlohmann::ordered_json report = {
      {"schema", "libtangent-check/2"},
      {"settings", gltf::toJson(options)},
      {"summary", {{"files", checks.size()}, {"primitives", primitives}, {"findings", findings}, {"unreadable", errors}}},
      {"files", files}};
  out << text::dumpJson(report, 2) << "\n";
}

namespace {

std::string seconds3(double seconds) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3f", seconds);
  return text;
}

}  // namespace

// JUnit XML as Jenkins and GitLab read it (the junit-10 schema's attributes): a suite per file,
// a test case per primitive and check, skipped cases for checks not run or ignored and for
// primitives not checked.
void writeJunit(std::ostream& out, const std::vector<gltf::FileCheck>& checks, const RunTimes& times) {
  std::ostringstream suites;
  std::size_t allTests = 0, allFailures = 0, allErrors = 0, allSkipped = 0;
  double allSeconds = 0;
  for (std::size_t i = 0; i < checks.size(); ++i) {
    const gltf::FileCheck& file = checks[i];
    const std::string fileAttribute = xmlEscape(file.file);
    std::ostringstream cases;
    std::size_t tests = 0, failures = 0, errors = 0, skipped = 0;
    auto open = [&](const std::string& classname, const std::string& name) {
      ++tests;
      cases << "    <testcase classname=\"" << classname << "\" name=\"" << xmlEscape(name) << "\" file=\"" << fileAttribute << "\"";
    };
    if (!file.error.empty()) {
      ++errors;
      open(fileAttribute, "load");
      cases << ">\n      <error message=\"" << xmlEscape(file.error) << "\"/>\n    </testcase>\n";
    }
    for (const auto& p : file.primitives) {
      const std::string classname = xmlEscape(file.file + " " + primitiveName(p));
      for (const auto& name : p.passed) {
        open(classname, name);
        cases << "/>\n";
      }
      for (const auto& f : p.findings) {
        ++failures;
        open(classname, f.check);
        cases << ">\n      <failure message=\"" << xmlEscape(findingSummary(f)) << "\" type=\"" << f.check << "\">";
        for (const auto& s : f.worst) cases << xmlEscape(s.detail) << "\n";
        cases << "</failure>\n    </testcase>\n";
      }
      for (const auto& [names, why] : {std::pair{&p.notRun, "an earlier check failed"}, std::pair{&p.ignored, "ignored (--only/--ignore)"}}) {
        for (const auto& name : *names) {
          ++skipped;
          open(classname, name);
          cases << ">\n      <skipped message=\"" << why << "\"/>\n    </testcase>\n";
        }
      }
    }
    // Warnings (accepted, not failures) as the suite's standard output, a line per warning
    // naming its primitive: JUnit has no warning state, and Jenkins shows the suite's output.
    std::string warnings;
    for (const auto& p : file.primitives)
      for (const auto& warning : p.warnings) warnings += "WARN " + primitiveName(p) + ": " + warning + "\n";
    for (const auto& reason : file.skipped) {
      const std::size_t colon = reason.find(": ");
      ++skipped;
      open(xmlEscape(file.file + " " + reason.substr(0, colon)), "primitive");
      cases << ">\n      <skipped message=\"" << xmlEscape(colon == std::string::npos ? reason : reason.substr(colon + 2))
            << "\"/>\n    </testcase>\n";
    }
    // --identify: the generator named per primitive, as suite properties.
    std::string properties;
    for (const auto& p : file.primitives)
      if (!p.generator.empty())
        properties += "      <property name=\"" + xmlEscape("generator " + primitiveName(p)) + "\" value=\"" + xmlEscape(p.generator) + "\"/>\n";
    suites << "  <testsuite name=\"" << fileAttribute << "\" tests=\"" << tests << "\" failures=\"" << failures << "\" errors=\""
           << errors << "\" skipped=\"" << skipped << "\" time=\"" << seconds3(file.seconds) << "\" timestamp=\""
           << times.startedUtc[i] << "\" file=\"" << fileAttribute << "\">\n";
    if (!properties.empty()) suites << "    <properties>\n" << properties << "    </properties>\n";
    suites << cases.str();
    if (!warnings.empty()) suites << "    <system-out>" << xmlEscape(warnings) << "</system-out>\n";
    suites << "  </testsuite>\n";
    allTests += tests;
    allFailures += failures;
    allErrors += errors;
    allSkipped += skipped;
    allSeconds += file.seconds;
  }
  out << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<testsuites name=\"tangent check\" tests=\"" << allTests << "\" failures=\""
      << allFailures << "\" errors=\"" << allErrors << "\" skipped=\"" << allSkipped << "\" time=\"" << seconds3(allSeconds)
      << "\">\n" << suites.str() << "</testsuites>\n";
}

namespace {

// GitHub Actions workflow commands: `::error file=F,title=T::message`. Data escapes % CR LF;
// property values also : and , (actions/toolkit, command.ts).
// Control characters (ESC: the runner's log is a terminal) and bytes that are not UTF-8 as \xHH.
std::string githubData(const std::string& raw) {
  std::string out;
  for (char c : text::terminalSafeLines(raw, 4096)) {
    if (c == '%') out += "%25";
    else if (c == '\r') out += "%0D";
    else if (c == '\n') out += "%0A";
    else out += c;
  }
  return out;
}

std::string githubProperty(const std::string& text) {
  std::string out;
  for (char c : githubData(text)) {
    if (c == ':') out += "%3A";
    else if (c == ',') out += "%2C";
    else out += c;
  }
  return out;
}

}  // namespace

void writeGithub(std::ostream& out, const std::vector<gltf::FileCheck>& checks) {
  std::size_t primitives = 0, findings = 0, errors = 0;
  for (const auto& file : checks) {
    if (!file.error.empty()) {
      ++errors;
      out << "::error file=" << githubProperty(file.file) << ",title=" << githubProperty("tangent check: unreadable") << "::"
          << githubData(file.error) << "\n";
    }
    for (const auto& p : file.primitives) {
      ++primitives;
      for (const auto& f : p.findings) {
        ++findings;
        std::string message = primitiveName(p) + ": " + findingSummary(f);
        if (!f.worst.empty()) message += "\nworst: " + f.worst.front().detail;
        out << "::error file=" << githubProperty(file.file) << ",title=" << githubProperty("tangent check " + f.check + " (" + primitiveName(p) + ")")
            << "::" << githubData(message) << "\n";
      }
      for (const auto& warning : p.warnings)
        out << "::warning file=" << githubProperty(file.file) << ",title=" << githubProperty("tangent check (" + primitiveName(p) + ")")
            << "::" << githubData(warning) << "\n";
    }
  }
  out << "::notice title=tangent check::" << checks.size() << " file(s), " << primitives << " primitive(s) checked, " << findings
      << " finding(s)" << (errors ? ", " + std::to_string(errors) + " unreadable" : "") << "\n";
}

namespace {

const char* checkDescription(std::size_t index) {
  static const char* descriptions[] = {
      "A primitive whose material has a normal texture stores TANGENT.",
      "TANGENT is VEC4 of FLOAT or normalized BYTE/SHORT, one element per vertex, on a UV set the primitive has.",
      "TANGENT components are finite.",
      "|xyz| is 1 within the rounding of the component type.",
      "w is exactly +1 or -1.",
      "w is the same on the three corners of a triangle.",
      "xyz is orthogonal to NORMAL within the tolerance and the rounding of both.",
      "w agrees with the triangle's orientation in the normal texture's UV set (w = -sign(UV area)).",
      "TANGENT agrees with freshly computed tangents within the tolerance and the rounding of the inputs."};
  return descriptions[index];
}

// SARIF 2.1.0 (OASIS): one run, a rule per check, a result per finding located at the file and
// the primitive (a logical location named as a JSON pointer into the document); warnings as
// results of level "warning" under one more rule.
constexpr const char* kSarifWarningRule = "warning";

// The line on which an element (a JSON pointer) starts in a .gltf's text, for the reports that
// point code-review tools at lines (SARIF's region, GitLab's lines.begin); nullopt for a .glb or
// a mesh file, whose elements are on no line of text. Each .gltf is read once.
class ElementLines {
 public:
  std::optional<std::size_t> line(const std::string& file, const std::string& pointer) {
    auto [text, unread] = texts_.try_emplace(file);
    if (unread) {
      std::string extension = std::filesystem::path(file).extension().string();
      for (char& c : extension) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
      if (extension == ".gltf") {
        std::ifstream in(file, std::ios::binary);
        text->second.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
      }
    }
    return text->second.empty() ? std::nullopt : text::jsonPointerLine(text->second, pointer);
  }

 private:
  std::map<std::string, std::string> texts_;
};

nlohmann::ordered_json primitiveLocations(const nlohmann::ordered_json& artifact, const gltf::PrimitiveCheck& p,
                                          std::optional<std::size_t> line) {
  using Json = nlohmann::ordered_json;
  Json physical = {{"artifactLocation", artifact}};
  if (line) physical["region"] = {{"startLine", *line}};
  return Json::array({{{"physicalLocation", physical},
                       {"logicalLocations", Json::array({{{"name", primitiveName(p)}, {"fullyQualifiedName", primitivePointer(p)}, {"kind", "object"}}})}}});
}

}  // namespace

void writeSarif(std::ostream& out, const std::vector<gltf::FileCheck>& checks, const gltf::CheckOptions& options) {
  using Json = nlohmann::ordered_json;
  ElementLines lines;
  Json rules = Json::array();
  for (std::size_t i = 0; i < gltf::kCheckCount; ++i)
    rules.push_back({{"id", gltf::kCheckNames[i]}, {"name", gltf::kCheckNames[i]}, {"shortDescription", {{"text", checkDescription(i)}}},
                     {"defaultConfiguration", {{"level", "error"}, {"enabled", options.enabled.test(i)}}}});
  // Warnings (PrimitiveCheck::warnings): accepted, not failures; one rule after the checks.
  const std::size_t warningRule = rules.size();
  rules.push_back({{"id", kSarifWarningRule},
                   {"name", kSarifWarningRule},
                   {"shortDescription", {{"text", "Accepted, but not as the glTF specification asks (NORMAL not unit length); not a failure."}}},
                   {"defaultConfiguration", {{"level", "warning"}}}});
  Json results = Json::array(), notifications = Json::array(), generators = Json::array();
  for (const auto& file : checks) {
    const Json artifact = {{"uri", text::uriPath(file.file)}};
    // --identify: the generator named per primitive, in the run's property bag.
    for (const auto& p : file.primitives)
      if (!p.generator.empty())
        generators.push_back({{"uri", artifact["uri"]},
                              {"primitive", primitivePointer(p)},
                              {"generator", p.generator}});
    if (!file.error.empty())
      notifications.push_back({{"level", "error"}, {"message", {{"text", file.error}}},
                               {"locations", Json::array({{{"physicalLocation", {{"artifactLocation", artifact}}}}})}});
    for (const auto& p : file.primitives) {
      for (const auto& f : p.findings) {
        const std::size_t ruleIndex = static_cast<std::size_t>(*gltf::parseCheck(f.check));
        Json properties = {{"unit", f.unit}, {"failed", f.failed}, {"total", f.total}, {"severityUnit", f.severityUnit}};
        Json worst = Json::array();
        for (const auto& s : f.worst) worst.push_back({{"element", s.element}, {"severity", s.severity}, {"detail", s.detail}});
        properties["worst"] = worst;
        results.push_back(
            {{"ruleId", f.check},
             {"ruleIndex", ruleIndex},
             {"level", "error"},
             {"message", {{"text", primitiveName(p) + ": " + findingSummary(f)}}},
             {"locations", primitiveLocations(artifact, p, lines.line(file.file, primitivePointer(p)))},
             {"properties", properties}});
      }
      for (const auto& warning : p.warnings)
        results.push_back({{"ruleId", kSarifWarningRule},
                           {"ruleIndex", warningRule},
                           {"level", "warning"},
                           {"message", {{"text", primitiveName(p) + ": " + warning}}},
                           {"locations", primitiveLocations(artifact, p, lines.line(file.file, primitivePointer(p)))}});
    }
  }
  bool unreadable = false;
  for (const auto& file : checks) unreadable = unreadable || !file.error.empty();
  Json invocation = {{"executionSuccessful", !unreadable}};
  if (!notifications.empty()) invocation["toolExecutionNotifications"] = notifications;
  invocation["properties"] = {{"settings", gltf::toJson(options)}};
  Json log = {
      {"$schema", "https://json.schemastore.org/sarif-2.1.0.json"},
      {"version", "2.1.0"},
      {"runs", Json::array({{{"tool", {{"driver", {{"name", "tangent check"},
                                                   {"informationUri", "https://github.com/KhronosGroup/glTF/tree/main/specification/2.0"},
                                                   {"rules", rules}}}}},
                             {"invocations", Json::array({invocation})},
                             {"results", results}}})}};
  if (!generators.empty()) log["runs"][0]["properties"] = {{"generators", generators}};
  out << text::dumpJson(log, 2) << "\n";
}

namespace {

// GitLab code quality (artifacts:reports:codequality, a subset of the Code Climate issue spec):
// a JSON array of issues with description, check_name, fingerprint, severity and location.path
// with location.lines.begin: in a .gltf the line its primitive starts on, in a .glb (whose
// elements are on no line of text) 1; the description names the element by its JSON pointer. GitLab matches an issue between the target
// branch and the merge request by its fingerprint, the SHA-256 of the file, the element and the
// rule: the same while the finding stays, whatever its counts; unique within a report.
std::string codeClimatePath(const std::string& file) {
  return std::filesystem::path(file).lexically_normal().generic_string();  // "./a.glb": "a.glb"
}

// A warning's rule: its words before the first ':' without the numbers in them ("reference
// compared only 682 of 23322 corners (2.9%, ..." and "NORMAL is not unit length: worst 0.06"
// keep one fingerprint while the counts change).
std::string warningKind(const std::string& warning) {
  std::string kind;
  for (char c : warning.substr(0, warning.find(':')))
    if (!std::isdigit(static_cast<unsigned char>(c))) kind += c;
  return kind;
}

}  // namespace

void writeCodeClimate(std::ostream& out, const std::vector<gltf::FileCheck>& checks) {
  using Json = nlohmann::ordered_json;
  Json issues = Json::array();
  std::map<std::string, std::size_t> seen;  // fingerprint input -> earlier issues with it
  ElementLines lines;
  // `kind` tells a primitive's warnings apart (they share one rule).
  auto add = [&](const gltf::FileCheck& file, const std::string& element, const std::string& rule, const char* severity,
                 const std::string& description, const std::string& kind = {}) {
    const std::string path = codeClimatePath(file.file);
    std::string identity = path + '\0' + element + '\0' + rule + '\0' + kind;
    if (const std::size_t earlier = seen[identity]++; earlier > 0) identity += '\0' + std::to_string(earlier);
    issues.push_back({{"type", "issue"},
                      {"description", description},
                      {"check_name", "tangent-check/" + rule},
                      {"fingerprint", gltf::sha256Hex(identity)},
                      {"severity", severity},
                      {"location", {{"path", path}, {"lines", {{"begin", lines.line(file.file, element).value_or(1)}}}}}});
  };
  for (const auto& file : checks) {
    if (!file.error.empty()) add(file, "", "unreadable", "blocker", "tangent check: unreadable: " + file.error);
    for (const auto& p : file.primitives) {
      const std::string element = primitiveName(p) + " (" + primitivePointer(p) + ")";
      for (const auto& f : p.findings) {
        std::string description = "tangent check " + f.check + ": " + element + ": " + findingSummary(f);
        if (!f.worst.empty()) description += "; worst: " + f.worst.front().detail;
        add(file, primitivePointer(p), f.check, "major", description);
      }
      for (const auto& warning : p.warnings)
        add(file, primitivePointer(p), "warning", "minor", "tangent check warning: " + element + ": " + warning, warningKind(warning));
    }
  }
  out << text::dumpJson(issues, 2) << "\n";
}

}  // namespace tangent::cli
