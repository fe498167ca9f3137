#include "lbm/percolation.hpp"

#include "common/error.hpp"

#include <array>
#include <cstdint>
#include <limits>
#include <vector>

namespace aniso::lbm {

namespace {

// The 18 non-rest D3Q19 directions: one or two axes at +-1.
std::vector<std::array<int, 3>> d3q19_links() {
  std::vector<std::array<int, 3>> links;
  for (int a = -1; a <= 1; ++a)
    for (int b = -1; b <= 1; ++b)
      for (int c = -1; c <= 1; ++c) {
        const int nonzero = (a != 0) + (b != 0) + (c != 0);
        if (nonzero == 1 || nonzero == 2) links.push_back({a, b, c});
      }
  return links;
}

} // namespace

bool percolates(const h5::VoxelImage& image, int axis, const Faces& faces) {
  const std::array<std::int64_t, 3> n{static_cast<std::int64_t>(image.shape[0]),
                                      static_cast<std::int64_t>(image.shape[1]),
                                      static_cast<std::int64_t>(image.shape[2])};
  if (faces[static_cast<std::size_t>(axis)] != FaceKind::periodic) return false;
  const std::size_t size = image.size();
  require_input(size < std::numeric_limits<std::uint32_t>::max(),
                "percolation check: images of 2^32 voxels or more are not supported");
  const auto links = d3q19_links();
  // Unwrapped offset of each reached void voxel along `axis`, in periods (the other axes' offsets
  // cannot reveal a wrap along this one); unreached voxels hold the sentinel. A path is at most
  // `size` links long, so offsets fit in 32 bits: 4 bytes per voxel.
  constexpr std::int32_t unreached = std::numeric_limits<std::int32_t>::min();
  const auto along = static_cast<std::size_t>(axis);
  std::vector<std::int32_t> offset(size, unreached);
  std::vector<std::uint32_t> queue;
  for (std::size_t seed = 0; seed < size; ++seed) {
    if (image.phase[seed] != 0 || offset[seed] != unreached) continue;
    offset[seed] = 0;
    queue.assign(1, static_cast<std::uint32_t>(seed));
    for (std::size_t head = 0; head < queue.size(); ++head) {
      const std::int64_t index = queue[head];
      const std::array<std::int64_t, 3> at{index % n[0], (index / n[0]) % n[1], index / (n[0] * n[1])};
      const std::int32_t here = offset[static_cast<std::size_t>(index)];
      for (const auto& link : links) {
        std::array<std::int64_t, 3> to{};
        std::int32_t lifted = here;
        bool blocked = false;
        for (std::size_t a = 0; a < 3; ++a) {
          to[a] = at[a] + link[a];
          if (to[a] >= 0 && to[a] < n[a]) continue;
          if (faces[a] != FaceKind::periodic) {
            blocked = true; // a wall face: no link leaves the cell here
            break;
          }
          const std::int64_t shift = to[a] < 0 ? -1 : 1;
          to[a] -= shift * n[a];
          if (a == along) lifted += static_cast<std::int32_t>(shift);
        }
        if (blocked) continue;
        const auto next = static_cast<std::size_t>(to[0] + n[0] * (to[1] + n[1] * to[2]));
        if (image.phase[next] != 0) continue;
        if (offset[next] == unreached) {
          offset[next] = lifted;
          queue.push_back(static_cast<std::uint32_t>(next));
        } else if (offset[next] != lifted) {
          return true; // the same voxel reached one period apart: a path around the cell
        }
      }
    }
  }
  return false;
}

} // namespace aniso::lbm
