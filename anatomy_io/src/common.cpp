#include "common.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <limits>
#include <system_error>
#include <utility>

#include "palpa/anatomy/import_error.hpp"
#include "palpa/anatomy_io/anatomy_io.hpp"

namespace palpa::anatomy_io::detail {

void fail(const fs::path& file, std::string_view place, std::string_view what) {
  std::string line = fmt::format("{}: {}: {}", file.string(), place, what);
  std::replace_if(line.begin(), line.end(), [](char c) { return c == '\n' || c == '\r'; }, ' ');
  throw anatomy::ImportError(line);
}

std::uintmax_t checked_file_size(const fs::path& file) {
  std::error_code ec;
  const fs::file_status status = fs::status(file, ec);
  if (ec || !fs::exists(status)) fail(file, "file", "does not exist");
  if (!fs::is_regular_file(status)) fail(file, "file", "is not a regular file");
  const std::uintmax_t size = fs::file_size(file, ec);
  if (ec) fail(file, "file", "its size cannot be read: " + ec.message());
  if (size > kMaxFileBytes) {
    fail(file, "file", fmt::format("{} bytes, more than the {} read", size, kMaxFileBytes));
  }
  return size;
}

std::string lower_trimmed(std::string_view text) {
  std::size_t b = 0;
  std::size_t e = text.size();
  while (b < e && std::isspace(static_cast<unsigned char>(text[b]))) ++b;
  while (e > b && std::isspace(static_cast<unsigned char>(text[e - 1]))) --e;
  std::string out(text.substr(b, e - b));
  for (char& c : out) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return out;
}

std::string lower_extension(const fs::path& file) {
  const std::string name = lower_trimmed(file.filename().string());
  if (name.size() > 7 && name.ends_with(".nii.gz")) return ".nii.gz";
  const std::size_t dot = name.rfind('.');
  return dot == std::string::npos || dot == 0 ? std::string() : name.substr(dot);
}

bool parse_int64(std::string_view text, std::int64_t& value) {
  const std::string t = lower_trimmed(text);
  if (t.empty()) return false;
  const char* begin = t.data() + (t[0] == '+' ? 1 : 0);
  const auto [end, ec] = std::from_chars(begin, t.data() + t.size(), value);
  return ec == std::errc() && end == t.data() + t.size();
}

bool parse_double(std::string_view text, double& value) {
  const std::string t = lower_trimmed(text);
  if (t.empty()) return false;
  const char* begin = t.data() + (t[0] == '+' ? 1 : 0);
  const auto [end, ec] = std::from_chars(begin, t.data() + t.size(), value);
  return ec == std::errc() && end == t.data() + t.size();
}

bool parse_doubles(std::string_view text, std::vector<double>& values) {
  values.clear();
  std::size_t i = 0;
  while (i < text.size()) {
    while (i < text.size() && std::isspace(static_cast<unsigned char>(text[i]))) ++i;
    std::size_t j = i;
    while (j < text.size() && !std::isspace(static_cast<unsigned char>(text[j]))) ++j;
    if (j > i) {
      double v = 0;
      if (!parse_double(text.substr(i, j - i), v) || values.size() >= 64) return false;
      values.push_back(v);
    }
    i = j;
  }
  return true;
}

std::size_t scalar_bytes(Scalar type) {
  switch (type) {
    case Scalar::u8:
    case Scalar::i8: return 1;
    case Scalar::u16:
    case Scalar::i16: return 2;
    case Scalar::u32:
    case Scalar::i32:
    case Scalar::f32: return 4;
    case Scalar::f64: return 8;
  }
  return 1;
}

void set_from_columns(const fs::path& file, const char* field, const std::array<std::array<double, 3>, 3>& columns,
                      Geometry& geometry) {
  for (int c = 0; c < 3; ++c) {
    const auto& v = columns[static_cast<std::size_t>(c)];
    const double length = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    if (!std::isfinite(length)) fail(file, field, fmt::format("axis {} is not finite", c));
    if (!(length > 0)) fail(file, field, fmt::format("axis {} has zero length (spacing must be positive)", c));
    geometry.spacing[static_cast<std::size_t>(c)] = length;
    for (int r = 0; r < 3; ++r) {
      geometry.direction[static_cast<std::size_t>(3 * r + c)] = v[static_cast<std::size_t>(r)] / length;
    }
  }
}

void flip_xy(Geometry& geometry) {
  for (int r = 0; r < 2; ++r) {
    geometry.origin[static_cast<std::size_t>(r)] = -geometry.origin[static_cast<std::size_t>(r)];
    for (int c = 0; c < 3; ++c) {
      auto& d = geometry.direction[static_cast<std::size_t>(3 * r + c)];
      d = -d;
    }
  }
}

namespace {

void check_dims(const fs::path& file, const Geometry& g, const char* field) {
  std::uintmax_t total = 1;
  for (std::size_t a = 0; a < 3; ++a) {
    if (g.dims[a] <= 0) fail(file, field, fmt::format("axis {} has {} voxels; must be at least 1", a, g.dims[a]));
    if (static_cast<std::uintmax_t>(g.dims[a]) > anatomy::kMaxVoxels) {
      fail(file, field, fmt::format("axis {} has {} voxels, more than the {} a volume may have", a, g.dims[a],
                                    anatomy::kMaxVoxels));
    }
    total *= static_cast<std::uintmax_t>(g.dims[a]);  // each <= 2^27: no overflow in 64 bits until checked
    if (total > anatomy::kMaxVoxels) {
      fail(file, field, fmt::format("{} x {} x {} voxels, more than the {} a volume may have", g.dims[0], g.dims[1],
                                    g.dims[2], anatomy::kMaxVoxels));
    }
  }
}

void check_direction(const fs::path& file, const Geometry& g, const char* field) {
  for (double d : g.direction) {
    if (!std::isfinite(d)) fail(file, field, "not finite");
  }
  for (int a = 0; a < 3; ++a) {
    for (int b = 0; b < 3; ++b) {
      double dot = 0;
      for (int r = 0; r < 3; ++r) {
        dot += g.direction[static_cast<std::size_t>(3 * r + a)] * g.direction[static_cast<std::size_t>(3 * r + b)];
      }
      if (std::abs(dot - (a == b ? 1.0 : 0.0)) > 1e-3) {
        fail(file, field,
             fmt::format("the axes are not orthonormal (axis {} . axis {} = {:.6g}); sheared volumes are not read", a,
                         b, dot));
      }
    }
  }
}

}  // namespace

anatomy::LabelVolume checked_volume(const fs::path& file, const Geometry& g, const FieldNames& names) {
  check_dims(file, g, names.dims);
  for (std::size_t a = 0; a < 3; ++a) {
    if (!std::isfinite(g.spacing[a]) || !(g.spacing[a] > 0)) {
      fail(file, names.spacing, fmt::format("spacing {} along axis {} must be finite and positive", g.spacing[a], a));
    }
    if (!std::isfinite(g.origin[a])) fail(file, names.origin, fmt::format("coordinate {} is not finite", a));
  }
  check_direction(file, g, names.direction);
  anatomy::LabelVolume volume;
  for (std::size_t a = 0; a < 3; ++a) volume.dims[a] = static_cast<int>(g.dims[a]);
  volume.spacing = g.spacing;
  volume.origin = g.origin;
  volume.direction = g.direction;
  return volume;
}

void check_raw_length(const fs::path& file, std::uintmax_t available, std::uintmax_t needed) {
  if (available < needed) {
    fail(file, "data", fmt::format("truncated: the header needs {} bytes of voxels, the file holds {}", needed, available));
  }
}

void check_compressed_length(const fs::path& file, std::uintmax_t compressed, std::uintmax_t needed) {
  if (compressed * 1032 + 1024 < needed) {
    fail(file, "data",
         fmt::format("truncated: {} compressed bytes cannot hold the {} bytes of voxels the header needs", compressed,
                     needed));
  }
}

std::string number(double value) { return fmt::format("{}", value); }

}  // namespace palpa::anatomy_io::detail
