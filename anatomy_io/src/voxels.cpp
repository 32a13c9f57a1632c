// The byte stream under the volume readers and the conversion of stored values to labels.
#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstring>
#include <limits>
#include <type_traits>
#include <utility>

#include "common.hpp"

namespace palpa::anatomy_io::detail {

ByteSource::ByteSource(fs::path file, const fs::path& data, std::uintmax_t offset, bool compressed)
    : file_(std::move(file)), in_(data, std::ios::binary), compressed_(compressed) {
  if (!in_) fail(file_, "file", fmt::format("{} cannot be opened", data.filename().string()));
  in_.seekg(static_cast<std::streamoff>(offset));
  if (!in_) fail(file_, "data", fmt::format("truncated: the data would start at byte {}", offset));
  if (compressed_) {
    buffer_.resize(std::size_t{1} << 16);
    if (inflateInit2(&zs_, 15 + 32) != Z_OK) fail(file_, "data", "zlib cannot be initialised");
  }
}

ByteSource::~ByteSource() {
  if (compressed_) inflateEnd(&zs_);
}

void ByteSource::read(unsigned char* out, std::size_t n, std::string_view place) {
  if (compressed_) {
    inflate_into(out, n, place);
    return;
  }
  in_.read(reinterpret_cast<char*>(out), static_cast<std::streamsize>(n));
  if (static_cast<std::size_t>(in_.gcount()) != n) {
    fail(file_, place, fmt::format("truncated: {} bytes expected, {} left in the file", n, in_.gcount()));
  }
}

void ByteSource::skip(std::uintmax_t n, std::string_view place) {
  unsigned char scratch[4096];
  while (n > 0) {
    const std::size_t step = n < sizeof scratch ? static_cast<std::size_t>(n) : sizeof scratch;
    read(scratch, step, place);
    n -= step;
  }
}

void ByteSource::inflate_into(unsigned char* out, std::size_t n, std::string_view place) {
  zs_.next_out = out;
  zs_.avail_out = static_cast<uInt>(n);
  while (zs_.avail_out > 0) {
    if (zs_.avail_in == 0) {
      in_.read(reinterpret_cast<char*>(buffer_.data()), static_cast<std::streamsize>(buffer_.size()));
      const auto got = static_cast<uInt>(in_.gcount());
      if (got == 0) {
        fail(file_, place, fmt::format("truncated: the compressed data ends {} bytes short", zs_.avail_out));
      }
      zs_.next_in = buffer_.data();
      zs_.avail_in = got;
    }
    const int result = inflate(&zs_, Z_NO_FLUSH);
    if (result == Z_STREAM_END) {
      ended_ = zs_.avail_out == 0;
      // Another gzip member may follow (concatenated streams); otherwise the data is short.
      if (zs_.avail_out > 0 && inflateReset(&zs_) != Z_OK) fail(file_, place, "zlib cannot continue");
      continue;
    }
    if (result == Z_BUF_ERROR && zs_.avail_in == 0) continue;
    if (result != Z_OK) {
      fail(file_, place,
           fmt::format("corrupt compressed data (zlib: {})", zs_.msg != nullptr ? zs_.msg : "error " + std::to_string(result)));
    }
  }
}

void ByteSource::finish(std::string_view place) {
  if (!compressed_ || ended_) return;
  unsigned char scratch[4096];
  for (int round = 0; round < 64; ++round) {  // at most 256 KiB past the voxels
    if (zs_.avail_in == 0) {
      in_.read(reinterpret_cast<char*>(buffer_.data()), static_cast<std::streamsize>(buffer_.size()));
      zs_.next_in = buffer_.data();
      zs_.avail_in = static_cast<uInt>(in_.gcount());
      if (zs_.avail_in == 0) fail(file_, place, "truncated: the compressed data ends before its checksum");
    }
    zs_.next_out = scratch;
    zs_.avail_out = sizeof scratch;
    const int result = inflate(&zs_, Z_NO_FLUSH);
    if (result == Z_STREAM_END) return;
    if (result != Z_OK && !(result == Z_BUF_ERROR && zs_.avail_in == 0)) {
      fail(file_, place,
           fmt::format("corrupt compressed data (zlib: {})", zs_.msg != nullptr ? zs_.msg : "error " + std::to_string(result)));
    }
  }
}

namespace {

template <typename T>
T load(const unsigned char* p, bool swap) {
  std::array<unsigned char, sizeof(T)> bytes;
  std::memcpy(bytes.data(), p, sizeof(T));
  if (swap) std::reverse(bytes.begin(), bytes.end());
  return std::bit_cast<T>(bytes);
}

std::string voxel_place(const anatomy::LabelVolume& v, std::size_t index) {
  const auto nx = static_cast<std::size_t>(v.dims[0]);
  const auto ny = static_cast<std::size_t>(v.dims[1]);
  return fmt::format("voxel ({}, {}, {})", index % nx, (index / nx) % ny, index / (nx * ny));
}

constexpr std::int64_t kLowest = std::numeric_limits<anatomy::Label>::min();
constexpr std::int64_t kHighest = std::numeric_limits<anatomy::Label>::max();

template <typename T>
void convert_typed(const fs::path& file, const unsigned char* data, std::size_t count, const Conversion& c,
                   std::size_t first, anatomy::LabelVolume& volume) {
  const bool scaled = c.slope != 1.0 || c.intercept != 0.0;
  for (std::size_t n = 0; n < count; ++n) {
    const T stored = load<T>(data + n * sizeof(T), c.swap);
    if constexpr (std::is_integral_v<T>) {
      if (!scaled) {
        const auto value = static_cast<std::int64_t>(stored);
        if (value < kLowest || value > kHighest) {
          fail(file, voxel_place(volume, first + n),
               fmt::format("label {} is outside {}..{} (labels are 32-bit integers)", value, kLowest, kHighest));
        }
        volume.labels[first + n] = static_cast<anatomy::Label>(value);
        continue;
      }
    }
    const double value = scaled ? c.slope * static_cast<double>(stored) + c.intercept : static_cast<double>(stored);
    if (!std::isfinite(value) || value != std::floor(value)) {
      fail(file, voxel_place(volume, first + n), fmt::format("value {} is not a whole number: not a label volume", value));
    }
    if (value < static_cast<double>(kLowest) || value > static_cast<double>(kHighest)) {
      fail(file, voxel_place(volume, first + n),
           fmt::format("label {} is outside {}..{} (labels are 32-bit integers)", value, kLowest, kHighest));
    }
    volume.labels[first + n] = static_cast<anatomy::Label>(value);
  }
}

}  // namespace

void convert_labels(const fs::path& file, const unsigned char* data, std::size_t count, const Conversion& c,
                    std::size_t first, anatomy::LabelVolume& volume) {
  switch (c.type) {
    case Scalar::u8: return convert_typed<std::uint8_t>(file, data, count, c, first, volume);
    case Scalar::i8: return convert_typed<std::int8_t>(file, data, count, c, first, volume);
    case Scalar::u16: return convert_typed<std::uint16_t>(file, data, count, c, first, volume);
    case Scalar::i16: return convert_typed<std::int16_t>(file, data, count, c, first, volume);
    case Scalar::u32: return convert_typed<std::uint32_t>(file, data, count, c, first, volume);
    case Scalar::i32: return convert_typed<std::int32_t>(file, data, count, c, first, volume);
    case Scalar::f32: return convert_typed<float>(file, data, count, c, first, volume);
    case Scalar::f64: return convert_typed<double>(file, data, count, c, first, volume);
  }
}

void read_labels(const fs::path& file, ByteSource& source, const Conversion& c, anatomy::LabelVolume& volume) {
  const std::size_t total = volume.voxel_count();
  const std::size_t size = scalar_bytes(c.type);
  volume.labels.assign(total, 0);
  std::vector<unsigned char> chunk(std::size_t{1} << 20);
  const std::size_t per_chunk = chunk.size() / size;
  for (std::size_t first = 0; first < total; first += per_chunk) {
    const std::size_t count = std::min(per_chunk, total - first);
    source.read(chunk.data(), count * size, "data");
    convert_labels(file, chunk.data(), count, c, first, volume);
  }
  source.finish("data");
}

std::vector<unsigned char> deflate_bytes(const unsigned char* data, std::size_t n, bool gzip) {
  z_stream zs{};
  if (deflateInit2(&zs, 6, Z_DEFLATED, gzip ? 15 + 16 : 15, 8, Z_DEFAULT_STRATEGY) != Z_OK) return {};
  std::vector<unsigned char> out(deflateBound(&zs, static_cast<uLong>(n)) + 64);
  zs.next_in = const_cast<unsigned char*>(data);  // zlib's API is not const-correct
  zs.avail_in = static_cast<uInt>(n);
  zs.next_out = out.data();
  zs.avail_out = static_cast<uInt>(out.size());
  const int result = deflate(&zs, Z_FINISH);
  out.resize(zs.total_out);
  deflateEnd(&zs);
  if (result != Z_STREAM_END) return {};
  return out;
}

void write_file(const fs::path& file, const std::string& header, const unsigned char* data, std::size_t n) {
  std::ofstream out(file, std::ios::binary | std::ios::trunc);
  if (!out) fail(file, "write", "cannot be created");
  out.write(header.data(), static_cast<std::streamsize>(header.size()));
  if (n > 0) out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(n));
  out.close();
  if (!out) fail(file, "write", "cannot be written");
}

}  // namespace palpa::anatomy_io::detail
