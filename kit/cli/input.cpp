#include "cli/input.h"

#include "cli/console.h"

namespace pcl_ncut_seg {
namespace tool {

std::vector<Flag> meshFlags() {
  std::vector<Flag> table = {
      intFlag("-samples", "N", "N points sampled uniformly by area instead of one per face, >= 1",
              "one per face", 1),
      intFlag("-seed", "S", "random seed of -samples, >= 0", "1", 0),
  };
  for (Flag& f : table)
    f.group = "mesh input";
  return table;
}

MeshSampling meshSampling(const Flags& flags) {
  MeshSampling s;
  if (flags.has("-samples"))
    s.samples = static_cast<std::size_t>(flags.integer("-samples"));
  if (flags.has("-seed"))
    s.seed = static_cast<std::uint64_t>(flags.integer("-seed"));
  s.given = flags.has("-samples") || flags.has("-seed");
  s.flag = flags.has("-samples") ? "-samples" : "-seed";
  return s;
}

bool loadInput(const std::string& path, const MeshSampling& sampling, Input& input) {
  std::string error;
  if (!files::readPointFile(path, sampling, input, error)) {
    fail(error);
    return false;
  }
  if (!input.mesh && sampling.given) {
    fail(sampling.flag + " applies to a mesh input (.off, .obj, .ply with faces); '" + path +
         "' holds points only");
    return false;
  }
  return true;
}

} // namespace tool
} // namespace pcl_ncut_seg
