// `tangent check`: text for people, JSON for tools (docs/check-json.md), JUnit XML for CI
// servers (one test case per primitive and check).
#include <fstream>
#include <iostream>
#include <sstream>

#include "commands.hpp"
#include "tangent/check.hpp"

namespace tangent::cli {
namespace {

const char* kCheckUsage =
    "usage: tangent check IN... [options]\n"
    "\n"
    "Checks the TANGENT of every primitive whose material has a normal texture: present, float\n"
    "or normalized VEC4, finite, unit (1e-3), w exactly +-1 and the same on a triangle's corners,\n"
    "orthogonal to NORMAL, handedness matching the normal texture's UV orientation, and close to\n"
    "freshly computed tangents.\n"
    "\n"
    "options:\n"
    "  --format FORMAT     text (default) | json | junit\n"
    "  -o, --output FILE   write the report to FILE instead of standard output\n"
    "  --tolerance DEG     for orthogonality and agreement (default 1)\n"
    "  --method NAME       mikktspace (default) | lengyel: what agreement is measured against\n"
    "  --all               check every triangle primitive (TEXCOORD_0 without a normal texture)\n"
    "  --asset-root DIR    folder buffer and image URIs may not leave (default: the input's folder)\n"
    "  -h, --help          this text\n"
    "exit codes: 0 clean, 1 findings, 2 unreadable input or usage error\n";

std::string xmlEscape(const std::string& text) {
  std::string out;
  for (char c : text) {
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

std::string primitiveName(const gltf::PrimitiveCheck& p) {
  return "mesh " + std::to_string(p.mesh) + (p.meshName.empty() ? "" : " '" + p.meshName + "'") + " primitive " +
         std::to_string(p.primitive);
}

std::string findingSummary(const gltf::CheckFinding& f) {
  return std::to_string(f.failed) + " of " + std::to_string(f.total) + " " + f.unit + ": " + f.message;
}

void writeText(std::ostream& out, const std::vector<gltf::FileCheck>& checks) {
  std::size_t primitives = 0, findings = 0, errors = 0;
  for (const auto& file : checks) {
    out << file.file << "\n";
    if (!file.error.empty()) {
      ++errors;
      out << "  ERROR " << file.error << "\n";
      continue;
    }
    for (const auto& p : file.primitives) {
      ++primitives;
      out << "  " << primitiveName(p) << " (TEXCOORD_" << p.texCoord << ", " << p.vertices << " vertices, " << p.triangles
          << " triangles): " << (p.findings.empty() ? "ok" : std::to_string(p.findings.size()) + " finding(s)") << "\n";
      for (const auto& f : p.findings) {
        ++findings;
        out << "    FAIL " << f.check << ": " << findingSummary(f) << "\n";
        for (const auto& s : f.worst) out << "         " << s.detail << "\n";
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
      if (p.referenceUndefined) out << "    (" << p.referenceUndefined << " corners have no defined reference frame; not compared)\n";
    }
    for (const auto& s : file.skipped) out << "  skipped " << s << "\n";
  }
  out << checks.size() << " file(s), " << primitives << " primitive(s) checked, " << findings << " finding(s)"
      << (errors ? ", " + std::to_string(errors) + " unreadable" : "") << "\n";
}

void writeJson(std::ostream& out, const std::vector<gltf::FileCheck>& checks) {
  nlohmann::ordered_json files = nlohmann::ordered_json::array();
  std::size_t findings = 0, errors = 0, primitives = 0;
  for (const auto& file : checks) {
    files.push_back(gltf::toJson(file));
    errors += !file.error.empty();
    primitives += file.primitives.size();
    for (const auto& p : file.primitives) findings += p.findings.size();
  }
  nlohmann::ordered_json report = {
      {"schema", "libtangent-check/1"},
      {"summary", {{"files", checks.size()}, {"primitives", primitives}, {"findings", findings}, {"unreadable", errors}}},
      {"files", files}};
  out << report.dump(2) << "\n";
}

void writeJunit(std::ostream& out, const std::vector<gltf::FileCheck>& checks) {
  std::ostringstream suites;
  std::size_t allTests = 0, allFailures = 0, allErrors = 0;
  for (const auto& file : checks) {
    std::ostringstream cases;
    std::size_t tests = 0, failures = 0, errors = 0;
    if (!file.error.empty()) {
      ++tests;
      ++errors;
      cases << "    <testcase classname=\"" << xmlEscape(file.file) << "\" name=\"load\">\n      <error message=\""
            << xmlEscape(file.error) << "\"/>\n    </testcase>\n";
    }
    for (const auto& p : file.primitives) {
      const std::string classname = xmlEscape(file.file + " " + primitiveName(p));
      for (const auto& name : p.passed) {
        ++tests;
        cases << "    <testcase classname=\"" << classname << "\" name=\"" << name << "\"/>\n";
      }
      for (const auto& f : p.findings) {
        ++tests;
        ++failures;
        cases << "    <testcase classname=\"" << classname << "\" name=\"" << f.check << "\">\n      <failure message=\""
              << xmlEscape(findingSummary(f)) << "\" type=\"" << f.check << "\">";
        for (const auto& s : f.worst) cases << xmlEscape(s.detail) << "\n";
        cases << "</failure>\n    </testcase>\n";
      }
      for (const auto& name : p.notRun) {
        ++tests;
        cases << "    <testcase classname=\"" << classname << "\" name=\"" << name << "\">\n      <skipped message=\"an earlier check failed\"/>\n    </testcase>\n";
      }
    }
    suites << "  <testsuite name=\"" << xmlEscape(file.file) << "\" tests=\"" << tests << "\" failures=\"" << failures
           << "\" errors=\"" << errors << "\">\n" << cases.str() << "  </testsuite>\n";
    allTests += tests;
    allFailures += failures;
    allErrors += errors;
  }
  out << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<testsuites name=\"tangent check\" tests=\"" << allTests << "\" failures=\""
      << allFailures << "\" errors=\"" << allErrors << "\">\n" << suites.str() << "</testsuites>\n";
}

int usageError(const std::string& message) {
  std::cerr << "tangent check: " << message << "\n\n" << kCheckUsage;
  return kExitUsage;
}

}  // namespace

int checkCommand(const std::vector<std::string>& args) {
  std::vector<std::string> inputs;
  std::string formatName = "text", output;
  gltf::CheckOptions options;
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& arg = args[i];
    const bool hasValue = i + 1 < args.size();
    if (arg == "-h" || arg == "--help") {
      std::cout << kCheckUsage;
      return kExitOk;
    } else if (arg == "--format") {
      if (!hasValue) return usageError("--format needs text, json or junit");
      formatName = args[++i];
      if (formatName != "text" && formatName != "json" && formatName != "junit") return usageError("--format must be text, json or junit");
    } else if (arg == "-o" || arg == "--output") {
      if (!hasValue) return usageError(arg + " needs a file name");
      output = args[++i];
    } else if (arg == "--tolerance") {
      if (!hasValue) return usageError("--tolerance needs degrees");
      try {
        std::size_t used = 0;
        options.toleranceDegrees = std::stod(args[++i], &used);
        if (used != args[i].size() || !(options.toleranceDegrees > 0) || options.toleranceDegrees > 180) throw std::invalid_argument("");
      } catch (const std::exception&) {
        return usageError("--tolerance must be a number of degrees in (0, 180]");
      }
    } else if (arg == "--method") {
      if (!hasValue || !parseMethod(args[++i], options.method) || options.method == Method::flat)
        return usageError("--method must be mikktspace or lengyel");
    } else if (arg == "--all") {
      options.all = true;
    } else if (arg == "--asset-root") {
      if (!hasValue) return usageError("--asset-root needs a directory");
      options.assetRoot = args[++i];
      if (!std::filesystem::is_directory(options.assetRoot)) return usageError("--asset-root " + args[i] + " is not a directory");
    } else if (!arg.empty() && arg[0] == '-') {
      return usageError("unknown option '" + arg + "'");
    } else {
      inputs.push_back(arg);
    }
  }
  if (inputs.empty()) return usageError("no input files");

  std::vector<gltf::FileCheck> checks;
  bool unreadable = false, findings = false;
  for (const auto& input : inputs) {
    checks.push_back(gltf::checkFile(input, options));
    unreadable = unreadable || !checks.back().error.empty();
    findings = findings || !checks.back().clean();
  }
  std::ostringstream report;
  if (formatName == "json") writeJson(report, checks);
  else if (formatName == "junit") writeJunit(report, checks);
  else writeText(report, checks);
  if (output.empty()) {
    std::cout << report.str();
  } else {
    std::ofstream file(output);
    file << report.str();
    if (!file) {
      std::cerr << "tangent check: cannot write " << output << "\n";
      return kExitUsage;
    }
  }
  for (const auto& check : checks) {
    if (!check.error.empty()) std::cerr << "error: " << check.error << "\n";
  }
  return unreadable ? kExitUsage : findings ? kExitInputFailed : kExitOk;
}

}  // namespace tangent::cli
