#include "support/text_files.h"

#include <cstdlib>
#include <fstream>
#include <regex>
#include <sstream>

#include <sys/wait.h>
#include <unistd.h>

namespace pcl_ncut_seg {
namespace test {

std::string readText(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

std::string quote(const std::string& s) {
  std::string q = "'";
  for (char c : s)
    q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

std::set<std::string> listDir(const std::filesystem::path& dir) {
  std::set<std::string> names;
  for (const auto& entry : std::filesystem::directory_iterator(dir))
    names.insert(entry.path().filename().string());
  return names;
}

std::vector<std::string> lines(const std::string& text) {
  const std::string plain = std::regex_replace(text, std::regex("\x1b\\[[0-9;]*m"), "");
  std::vector<std::string> result;
  std::stringstream ss(plain);
  std::string line;
  while (std::getline(ss, line))
    result.push_back(line);
  return result;
}

CommandRun runCommand(const std::string& command, const std::filesystem::path& out,
                      const std::filesystem::path& err) {
  const std::string line = command + " >" + quote(out.string()) + " 2>" + quote(err.string());
  const int status = std::system(line.c_str());
  CommandRun r;
  r.status = (status != -1 && WIFEXITED(status)) ? WEXITSTATUS(status) : -1;
  r.out = readText(out);
  r.err = readText(err);
  std::error_code ec;
  std::filesystem::remove(out, ec);
  std::filesystem::remove(err, ec);
  return r;
}

std::filesystem::path makeTempDir(const std::string& prefix) {
  std::string tmpl = (std::filesystem::temp_directory_path() / (prefix + "_XXXXXX")).string();
  if (::mkdtemp(tmpl.data()) == nullptr)
    return {};
  return tmpl;
}

} // namespace test
} // namespace pcl_ncut_seg
