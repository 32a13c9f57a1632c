// NIfTI-1 single files (.nii, .nii.gz), header parsed here (348 bytes, either byte order)
// rather than by vtkNIFTIImageReader: the sizes are checked before anything is allocated,
// and the world placement follows the NIfTI-1 standard's three methods exactly (the VTK
// reader reverses the slices when qfac = -1 and adjusts its matrices to match, which the
// label index order here must not do).
#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstring>

#include "common.hpp"

namespace palpa::anatomy_io::detail {
namespace {

constexpr std::size_t kHeaderBytes = 348;

struct Header {
  std::array<unsigned char, kHeaderBytes> raw{};
  bool swap = false;
  template <typename T>
  T at(std::size_t offset) const {
    std::array<unsigned char, sizeof(T)> bytes;
    std::memcpy(bytes.data(), raw.data() + offset, sizeof(T));
    if (swap) std::reverse(bytes.begin(), bytes.end());
    return std::bit_cast<T>(bytes);
  }
  std::int16_t dim(int n) const { return at<std::int16_t>(40 + 2 * static_cast<std::size_t>(n)); }
  double pixdim(int n) const { return static_cast<double>(at<float>(76 + 4 * static_cast<std::size_t>(n))); }
  double f(std::size_t offset) const { return static_cast<double>(at<float>(offset)); }
};

Scalar nifti_type(const fs::path& file, int datatype) {
  switch (datatype) {
    case 2: return Scalar::u8;
    case 4: return Scalar::i16;
    case 8: return Scalar::i32;
    case 16: return Scalar::f32;
    case 64: return Scalar::f64;
    case 256: return Scalar::i8;
    case 512: return Scalar::u16;
    case 768: return Scalar::u32;
    default: break;
  }
  fail(file, "datatype", fmt::format("{} is not a label type (integers of 8 to 32 bits, float or double)", datatype));
}

double unit_of(const Header& h) {
  switch (h.raw[123] & 0x07) {
    case 1: return 1.0;   // metre
    case 3: return 1e-6;  // micron
    default: return 1e-3;  // millimetre, and unknown (0), which tools write for millimetres
  }
}

void check_identity(const fs::path& file, Header& h) {
  const auto native = h.at<std::int32_t>(0);
  if (native != 348) {
    h.swap = true;
    const auto swapped = h.at<std::int32_t>(0);
    if (swapped == 540 || native == 540) fail(file, "sizeof_hdr", "a NIfTI-2 file; only NIfTI-1 is read");
    if (swapped != 348) fail(file, "sizeof_hdr", fmt::format("{}, not 348: not a NIfTI-1 file", native));
  }
  if (std::memcmp(h.raw.data() + 344, "ni1", 4) == 0) {
    fail(file, "magic", "a .hdr/.img pair; save the volume as a single .nii or .nii.gz");
  }
  if (std::memcmp(h.raw.data() + 344, "n+1", 4) != 0) fail(file, "magic", "not \"n+1\": not a NIfTI-1 file");
}

Geometry dims_of(const fs::path& file, const Header& h) {
  const int rank = h.dim(0);
  if (rank < 1 || rank > 7) fail(file, "dim", fmt::format("dim[0] = {}, must be 1 to 7", rank));
  Geometry g;
  for (int a = 1; a <= 3; ++a) g.dims[static_cast<std::size_t>(a - 1)] = a <= rank ? h.dim(a) : 1;
  for (int a = 4; a <= rank; ++a) {
    if (h.dim(a) != 1) {
      fail(file, "dim", fmt::format("dim[{}] = {}: a series or vector image, not a label volume", a, h.dim(a)));
    }
  }
  return g;
}

// NIfTI-1, method 2: rotation from the quaternion (b, c, d), a = sqrt(1 - b^2 - c^2 - d^2).
std::array<double, 9> quaternion_matrix(const fs::path& file, double b, double c, double d) {
  if (!std::isfinite(b) || !std::isfinite(c) || !std::isfinite(d)) fail(file, "quatern_b/c/d", "not finite");
  double a = 1.0 - (b * b + c * c + d * d);
  if (a < -1e-3) fail(file, "quatern_b/c/d", "b^2 + c^2 + d^2 is more than 1: not a rotation");
  if (a < 1e-7) {  // the standard's rule: a 180 degree rotation, (b, c, d) renormalised
    a = 1.0 / std::sqrt(b * b + c * c + d * d);
    b *= a;
    c *= a;
    d *= a;
    a = 0.0;
  } else {
    a = std::sqrt(a);
  }
  return {a * a + b * b - c * c - d * d, 2 * (b * c - a * d),         2 * (b * d + a * c),
          2 * (b * c + a * d),         a * a + c * c - b * b - d * d, 2 * (c * d - a * b),
          2 * (b * d - a * c),         2 * (c * d + a * b),         a * a + d * d - c * c - b * b};
}

FieldNames placement(const fs::path& file, const Header& h, Geometry& g) {
  const double unit = unit_of(h);
  if (h.at<std::int16_t>(254) > 0) {  // method 3: the sform's rows map (i, j, k, 1) to x, y, z
    std::array<std::array<double, 3>, 3> columns{};
    for (std::size_t r = 0; r < 3; ++r) {
      for (std::size_t c = 0; c < 3; ++c) columns[c][r] = h.f(280 + 16 * r + 4 * c) * unit;
      g.origin[r] = h.f(280 + 16 * r + 12) * unit;
    }
    set_from_columns(file, "srow", columns, g);
    return {"dim", "srow", "srow", "srow"};
  }
  for (int a = 0; a < 3; ++a) g.spacing[static_cast<std::size_t>(a)] = h.pixdim(a + 1) * unit;
  if (h.at<std::int16_t>(252) > 0) {  // method 2: R [pixdim1 i, pixdim2 j, qfac pixdim3 k] + qoffset
    g.direction = quaternion_matrix(file, h.f(256), h.f(260), h.f(264));
    const double qfac = h.pixdim(0) < 0 ? -1.0 : 1.0;
    for (std::size_t r = 0; r < 3; ++r) {
      g.direction[3 * r + 2] *= qfac;
      g.origin[r] = h.f(268 + 4 * r) * unit;
    }
    return {"dim", "pixdim", "qoffset", "quatern_b/c/d"};
  }
  return {"dim", "pixdim", "qoffset", "qform"};  // method 1: spacing only, axis-aligned
}

Conversion conversion_of(const fs::path& file, const Header& h) {
  Conversion c;
  c.type = nifti_type(file, h.at<std::int16_t>(70));
  c.swap = h.swap;
  const double slope = h.f(112);
  const double intercept = h.f(116);
  if (slope != 0.0) {  // 0 means "not scaled"
    if (!std::isfinite(slope) || !std::isfinite(intercept)) fail(file, "scl_slope", "not finite");
    c.slope = slope;
    c.intercept = intercept;
  }
  return c;
}

}  // namespace

anatomy::LabelVolume read_nifti(const fs::path& file, bool gzip) {
  const std::uintmax_t size = checked_file_size(file);
  ByteSource source(file, file, 0, gzip);
  Header h;
  source.read(h.raw.data(), kHeaderBytes, "header");
  check_identity(file, h);
  Geometry g = dims_of(file, h);
  const FieldNames names = placement(file, h, g);
  anatomy::LabelVolume volume = checked_volume(file, g, names);
  const Conversion c = conversion_of(file, h);
  const double offset = h.f(108);
  if (!std::isfinite(offset) || offset < 348 || offset != std::floor(offset) || offset > 1e9) {
    fail(file, "vox_offset", fmt::format("{} is not a byte offset of 348 or more", offset));
  }
  const auto start = static_cast<std::uintmax_t>(offset);
  const std::uintmax_t needed = volume.voxel_count() * scalar_bytes(c.type);
  if (gzip) {
    check_compressed_length(file, size, start + needed);
  } else {
    check_raw_length(file, size < start ? 0 : size - start, needed);
  }
  source.skip(start - kHeaderBytes, "vox_offset");
  read_labels(file, source, c, volume);
  return volume;
}

namespace {

// The NIfTI-1 standard's conversion of a rotation (determinant +1) to a quaternion (b, c, d)
// with a >= 0.
std::array<double, 3> quaternion_of(const std::array<double, 9>& m) {
  const double trace = m[0] + m[4] + m[8] + 1.0;
  double a, b, c, d;
  if (trace > 0.5) {
    a = 0.5 * std::sqrt(trace);
    b = 0.25 * (m[7] - m[5]) / a;
    c = 0.25 * (m[2] - m[6]) / a;
    d = 0.25 * (m[3] - m[1]) / a;
  } else {
    const double xd = 1.0 + m[0] - (m[4] + m[8]);
    const double yd = 1.0 + m[4] - (m[0] + m[8]);
    const double zd = 1.0 + m[8] - (m[0] + m[4]);
    if (xd > 1.0) {
      b = 0.5 * std::sqrt(xd);
      c = 0.25 * (m[1] + m[3]) / b;
      d = 0.25 * (m[2] + m[6]) / b;
      a = 0.25 * (m[7] - m[5]) / b;
    } else if (yd > 1.0) {
      c = 0.5 * std::sqrt(yd);
      b = 0.25 * (m[1] + m[3]) / c;
      d = 0.25 * (m[5] + m[7]) / c;
      a = 0.25 * (m[2] - m[6]) / c;
    } else {
      d = 0.5 * std::sqrt(zd);
      b = 0.25 * (m[2] + m[6]) / d;
      c = 0.25 * (m[5] + m[7]) / d;
      a = 0.25 * (m[3] - m[1]) / d;
    }
    if (a < 0.0) {
      b = -b;
      c = -c;
      d = -d;
    }
  }
  return {b, c, d};
}

template <typename T>
void put(std::array<unsigned char, 352>& raw, std::size_t offset, T value) {
  std::memcpy(raw.data() + offset, &value, sizeof(T));
}

}  // namespace

void write_nifti(const fs::path& file, const anatomy::LabelVolume& v, bool gzip) {
  static_assert(std::endian::native == std::endian::little, "the writers write the host's bytes as little-endian");
  check_writable(file, v);
  for (int n : v.dims) {
    if (n > 32767) fail(file, "dim", fmt::format("{} voxels along an axis; NIfTI-1 holds at most 32767", n));
  }
  std::array<unsigned char, 352> raw{};  // the header and the empty extension flag
  put<std::int32_t>(raw, 0, 348);
  const std::array<std::int16_t, 8> dim{3, static_cast<std::int16_t>(v.dims[0]), static_cast<std::int16_t>(v.dims[1]),
                                        static_cast<std::int16_t>(v.dims[2]), 1, 1, 1, 1};
  for (std::size_t n = 0; n < 8; ++n) put(raw, 40 + 2 * n, dim[n]);
  put<std::int16_t>(raw, 70, 8);  // DT_INT32: labels of any sign
  put<std::int16_t>(raw, 72, 32);
  const auto& d = v.direction;
  const double det = d[0] * (d[4] * d[8] - d[5] * d[7]) - d[1] * (d[3] * d[8] - d[5] * d[6]) +
                     d[2] * (d[3] * d[7] - d[4] * d[6]);
  std::array<double, 9> rotation = d;
  if (det < 0) {
    for (std::size_t r = 0; r < 3; ++r) rotation[3 * r + 2] = -rotation[3 * r + 2];
  }
  put<float>(raw, 76, det < 0 ? -1.0f : 1.0f);  // qfac
  for (std::size_t a = 0; a < 3; ++a) put(raw, 80 + 4 * a, static_cast<float>(v.spacing[a] * 1e3));
  put<float>(raw, 108, 352.0f);
  raw[123] = 2;                     // xyzt_units: millimetres
  put<std::int16_t>(raw, 252, 1);  // qform_code: scanner
  put<std::int16_t>(raw, 254, 1);  // sform_code: scanner
  const auto q = quaternion_of(rotation);
  for (std::size_t n = 0; n < 3; ++n) {
    put(raw, 256 + 4 * n, static_cast<float>(q[n]));
    put(raw, 268 + 4 * n, static_cast<float>(v.origin[n] * 1e3));
    for (std::size_t c = 0; c < 3; ++c) put(raw, 280 + 16 * n + 4 * c, static_cast<float>(d[3 * n + c] * v.spacing[c] * 1e3));
    put(raw, 280 + 16 * n + 12, static_cast<float>(v.origin[n] * 1e3));
  }
  std::memcpy(raw.data() + 344, "n+1", 4);
  std::string bytes(reinterpret_cast<const char*>(raw.data()), raw.size());
  bytes.append(reinterpret_cast<const char*>(v.labels.data()), v.labels.size() * sizeof(anatomy::Label));  // little-endian hosts
  if (!gzip) {
    write_file(file, bytes, nullptr, 0);
    return;
  }
  const auto packed = deflate_bytes(reinterpret_cast<const unsigned char*>(bytes.data()), bytes.size(), true);
  if (packed.empty()) fail(file, "write", "compression failed");
  write_file(file, std::string(), packed.data(), packed.size());
}

}  // namespace palpa::anatomy_io::detail
