// Every repository path a document or a source comment cites exists (issue 13: 28 files
// cited the dataset contract under a folder "spec", which is docs/rig-dataset.md). A
// citation is a word that starts with a top-level part (such as "docs/" or "protocol/") or any
// relative path of a document or source file; it resolves when some file or folder of the
// tree is it or ends with it (the top, a part's folder, a public header under
// include/tetrapulse/: "host/rig_clock.hpp"). Words that hold an ellipsis or an upper-case
// stand-in for a name or a number are templates, not citations.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace {

const fs::path kRoot = TETRAPULSE_SOURCE_DIR;

bool scanned(const fs::path& p) {
  const std::string ext = p.extension().string();
  return ext == ".md" || ext == ".cpp" || ext == ".hpp" || ext == ".cmake" || p.filename() == "CMakeLists.txt";
}

bool skipped_folder(const fs::path& p) {
  const std::string name = p.filename().string();
  return name == ".git" || name == "build" || name == "out" || name == "vectors" || name.rfind('.', 0) == 0;
}

// The lines of `file` that cite: all of a document, only comments of code.
std::vector<std::pair<int, std::string>> citing_lines(const fs::path& file) {
  std::ifstream in(file);
  std::vector<std::pair<int, std::string>> out;
  const bool code = file.extension() != ".md";
  std::string line;
  for (int n = 1; std::getline(in, line); ++n) {
    if (code) {
      if (line.find("#include") != std::string::npos) continue;
      const size_t c = std::min({line.find("//"), line.find("/*"), line.find('#')});
      const size_t star = line.find_first_not_of(" \t");
      if (c == std::string::npos && !(star != std::string::npos && line[star] == '*')) continue;
      if (c != std::string::npos) line = line.substr(c);
    }
    out.emplace_back(n, line);
  }
  return out;
}

// Every file and folder of the tree, relative to its top ("host/src/board.cpp").
std::vector<std::string> tree_paths() {
  std::vector<std::string> out;
  for (auto it = fs::recursive_directory_iterator(kRoot); it != fs::recursive_directory_iterator(); ++it) {
    const std::string name = it->path().filename().string();
    if (it->is_directory() && (name == "build" || name == "out" || name.rfind('.', 0) == 0)) {
      it.disable_recursion_pending();
      continue;
    }
    out.push_back(fs::relative(it->path(), kRoot).generic_string());
  }
  return out;
}

// Files a command writes (a board's target file, the demo's output folder) are outputs, not citations.
bool resolves(const std::string& cited, const std::vector<std::string>& tree) {
  static const std::regex kStandIn("(^|[/_.-])(NAME|ID|N|X)([/_.-]|$)");
  if (cited.find("...") != std::string::npos || std::regex_search(cited, kStandIn)) return true;
  if (cited.rfind("boards/", 0) == 0 || cited.rfind("out/", 0) == 0) return true;
  const std::string tail = "/" + cited;
  for (const std::string& p : tree) {
    if (p == cited || (p.size() > tail.size() && p.compare(p.size() - tail.size(), tail.size(), tail) == 0)) return true;
  }
  return false;
}

}  // namespace

TEST(CitedPaths, EveryCitedRepositoryPathExists) {
  // A top-level part's path, or any relative path of a document or source file.
  const std::regex citation(
      R"((?:^|[\s`'"(\[<])((?:protocol|firmware|host|localizer|datasets|sim|hardware|tests|bench|docs|scripts|cmake)/[\w./-]*\w|[\w-]+/[\w./-]*\.(?:md|cpp|hpp|yaml|cmake|sh)\b))");
  const std::vector<std::string> tree = tree_paths();
  std::vector<std::string> missing;
  size_t citations = 0;
  for (auto it = fs::recursive_directory_iterator(kRoot); it != fs::recursive_directory_iterator(); ++it) {
    if (it->is_directory() && skipped_folder(it->path())) {
      it.disable_recursion_pending();
      continue;
    }
    if (!it->is_regular_file() || !scanned(it->path())) continue;
    for (const auto& [n, line] : citing_lines(it->path())) {
      for (auto m = std::sregex_iterator(line.begin(), line.end(), citation); m != std::sregex_iterator(); ++m) {
        const std::string cited = (*m)[1].str();
        ++citations;
        if (!resolves(cited, tree)) {
          missing.push_back(fs::relative(it->path(), kRoot).string() + ":" + std::to_string(n) + ": " + cited);
        }
      }
    }
  }
  std::ostringstream list;
  for (const std::string& m : missing) list << "\n  " << m;
  EXPECT_GT(citations, 100u) << "the scan found almost no citations: is TETRAPULSE_SOURCE_DIR the tree?";
  EXPECT_TRUE(missing.empty()) << missing.size() << " cited paths do not exist:" << list.str();
}
