#include "support.hpp"

#include <cstdio>
#include <cstring>
#include <random>

namespace palpa::anatomy_io::test {

ScratchDir::ScratchDir() {
  std::random_device seed;
  path_ = fs::temp_directory_path() / ("palpa-anatomy-io-" + std::to_string(seed()) + "-" + std::to_string(seed()));
  fs::create_directories(path_);
}

ScratchDir::~ScratchDir() {
  std::error_code ec;
  fs::remove_all(path_, ec);
}

std::string read_bytes(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

void write_bytes(const fs::path& file, const std::string& bytes) {
  std::ofstream out(file, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

namespace {

using Columns = std::array<std::array<double, 3>, 3>;

void set_axes(anatomy::LabelVolume& v, const Columns& mm) {
  for (std::size_t c = 0; c < 3; ++c) {
    std::array<double, 3> f{};
    for (std::size_t r = 0; r < 3; ++r) f[r] = static_cast<double>(static_cast<float>(mm[c][r]));
    const double length = std::sqrt(f[0] * f[0] + f[1] * f[1] + f[2] * f[2]);
    v.spacing[c] = length * 1e-3;
    for (std::size_t r = 0; r < 3; ++r) v.direction[3 * r + c] = f[r] / length;
  }
}

}  // namespace

anatomy::LabelVolume oblique_ball() {
  anatomy::LabelVolume v;
  v.dims = {20, 24, 28};
  // Rotation about z by 30 degrees, then about x by 20 degrees.
  const double cz = std::cos(0.5235987755982988), sz = std::sin(0.5235987755982988);
  const double cx = std::cos(0.3490658503988659), sx = std::sin(0.3490658503988659);
  const std::array<double, 9> rot{cz, -sz, 0, cx * sz, cx * cz, -sx, sx * sz, sx * cz, cx};
  const std::array<double, 3> spacing_mm{0.7, 0.9, 1.3};
  Columns mm{};
  for (std::size_t c = 0; c < 3; ++c) {
    for (std::size_t r = 0; r < 3; ++r) mm[c][r] = rot[3 * r + c] * spacing_mm[c];
  }
  set_axes(v, mm);
  const std::array<double, 3> origin_mm{-12.25, 34.5, 56.125};  // exact in float
  for (std::size_t r = 0; r < 3; ++r) v.origin[r] = origin_mm[r] * 1e-3;
  v.labels.assign(v.voxel_count(), 0);
  for (int k = 0; k < v.dims[2]; ++k) {
    for (int j = 0; j < v.dims[1]; ++j) {
      for (int i = 0; i < v.dims[0]; ++i) {
        const int d2 = (i - 10) * (i - 10) + (j - 12) * (j - 12) + (k - 14) * (k - 14);
        if (d2 <= 36) v.labels[v.index(i, j, k)] = 3;
      }
    }
  }
  v.labels[v.index(3, 5, 7)] = 7;
  return v;
}

anatomy::LabelVolume permuted_flipped(const anatomy::LabelVolume& a) {
  anatomy::LabelVolume b;
  const int nx = a.dims[0], ny = a.dims[1], nz = a.dims[2];
  b.dims = {nz, nx, ny};
  b.spacing = {a.spacing[2], a.spacing[0], a.spacing[1]};
  for (std::size_t r = 0; r < 3; ++r) {
    b.direction[3 * r + 0] = -a.direction[3 * r + 2];
    b.direction[3 * r + 1] = a.direction[3 * r + 0];
    b.direction[3 * r + 2] = a.direction[3 * r + 1];
  }
  b.origin = a.world(0, 0, nz - 1);
  b.labels.assign(b.voxel_count(), 0);
  for (int k = 0; k < nz; ++k) {
    for (int j = 0; j < ny; ++j) {
      for (int i = 0; i < nx; ++i) b.labels[b.index(nz - 1 - k, i, j)] = a.labels[a.index(i, j, k)];
    }
  }
  return b;
}

std::array<double, 3> world_of_label(const anatomy::LabelVolume& v, anatomy::Label label) {
  std::array<double, 3> found{};
  int count = 0;
  for (int k = 0; k < v.dims[2]; ++k) {
    for (int j = 0; j < v.dims[1]; ++j) {
      for (int i = 0; i < v.dims[0]; ++i) {
        if (v.labels[v.index(i, j, k)] != label) continue;
        found = v.world(i, j, k);
        ++count;
      }
    }
  }
  EXPECT_EQ(count, 1) << "voxels with label " << label;
  return found;
}

std::array<double, 3> centroid_of_label(const anatomy::LabelVolume& v, anatomy::Label label) {
  std::array<double, 3> sum{};
  double count = 0;
  for (int k = 0; k < v.dims[2]; ++k) {
    for (int j = 0; j < v.dims[1]; ++j) {
      for (int i = 0; i < v.dims[0]; ++i) {
        if (v.labels[v.index(i, j, k)] != label) continue;
        const auto w = v.world(i, j, k);
        for (std::size_t r = 0; r < 3; ++r) sum[r] += w[r];
        count += 1;
      }
    }
  }
  EXPECT_GT(count, 0);
  for (double& s : sum) s /= count;
  return sum;
}

anatomy::TriangleMesh icosphere() {
  const double t = (1.0 + std::sqrt(5.0)) / 2.0;
  std::vector<std::array<double, 3>> p{{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0}, {0, -1, t}, {0, 1, t},
                                       {0, -1, -t}, {0, 1, -t}, {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
  std::vector<std::array<std::int32_t, 3>> f{{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                                             {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                                             {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                                             {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
  std::vector<std::array<std::int32_t, 3>> finer;
  std::vector<std::pair<std::pair<int, int>, int>> mids;
  auto mid = [&](int a, int b) {
    const auto key = std::make_pair(std::min(a, b), std::max(a, b));
    for (const auto& [k, v] : mids) {
      if (k == key) return v;
    }
    const auto& pa = p[static_cast<std::size_t>(a)];
    const auto& pb = p[static_cast<std::size_t>(b)];
    p.push_back({(pa[0] + pb[0]) / 2, (pa[1] + pb[1]) / 2, (pa[2] + pb[2]) / 2});
    mids.emplace_back(key, static_cast<int>(p.size() - 1));
    return static_cast<int>(p.size() - 1);
  };
  for (const auto& tri : f) {
    const int ab = mid(tri[0], tri[1]), bc = mid(tri[1], tri[2]), ca = mid(tri[2], tri[0]);
    finer.push_back({tri[0], ab, ca});
    finer.push_back({tri[1], bc, ab});
    finer.push_back({tri[2], ca, bc});
    finer.push_back({ab, bc, ca});
  }
  anatomy::TriangleMesh mesh;
  for (auto& q : p) {
    const double n = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2]);
    mesh.points.push_back({0.05 * q[0] / n, 0.05 * q[1] / n, 0.05 * q[2] / n});
  }
  mesh.triangles = finer;
  return mesh;
}

// A NIfTI-1 header written byte by byte: 4 x 5 x 6 uint8, pixdim 2, 3, 4 mm, voxel (1, 2, 3)
// labelled 5.
std::string nifti_header(float qfac, short qform_code, short sform_code) {
  std::string h(352, '\0');
  auto put = [&h](std::size_t at, auto value) { std::memcpy(h.data() + at, &value, sizeof value); };
  put(0, std::int32_t{348});
  const std::int16_t dim[8] = {3, 4, 5, 6, 1, 1, 1, 1};
  std::memcpy(h.data() + 40, dim, sizeof dim);
  put(70, std::int16_t{2});
  put(72, std::int16_t{8});
  const float pixdim[8] = {qfac, 2, 3, 4, 1, 1, 1, 1};
  std::memcpy(h.data() + 76, pixdim, sizeof pixdim);
  put(108, 352.0f);
  h[123] = 2;  // mm
  put(252, qform_code);
  put(254, sform_code);
  put(256, 0.0f);                 // quatern_b
  put(260, 0.0f);                 // quatern_c
  put(264, 0.70710678118654752f);  // quatern_d: 90 degrees about z
  put(268, 10.0f);
  put(272, 20.0f);
  put(276, 30.0f);
  const float srow[12] = {0, 0, -2.5f, 7, 1.5f, 0, 0, 8, 0, 3.5f, 0, 9};
  std::memcpy(h.data() + 280, srow, sizeof srow);
  std::memcpy(h.data() + 344, "n+1", 4);
  std::string data(4 * 5 * 6, '\0');
  data[1 + 4 * (2 + 5 * 3)] = 5;
  return h + data;
}

void expect_refusal_names(const std::string& what, const fs::path& file, const std::vector<std::string>& parts) {
  std::printf("refused: %s\n", what.c_str());  // what the user reads
  EXPECT_EQ(what.find('\n'), std::string::npos) << what;
  EXPECT_NE(what.find(file.filename().string()), std::string::npos) << what;
  for (const auto& part : parts) EXPECT_NE(what.find(part), std::string::npos) << "missing \"" << part << "\" in: " << what;
}

}  // namespace palpa::anatomy_io::test
