#pragma once
// Shared by the readers and writers of anatomy_io (internal): one-line refusals, the file
// size guard, the checks of a volume's header before allocation, a raw-or-compressed byte
// stream and the conversion of voxel values to labels.
#include <zlib.h>

#include <array>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>
#include <vector>

#include "palpa/anatomy/label_volume.hpp"

namespace palpa::anatomy_io::detail {

namespace fs = std::filesystem;

/// Throws ImportError "FILE: PLACE: WHAT", newlines in WHAT turned into spaces.
[[noreturn]] void fail(const fs::path& file, std::string_view place, std::string_view what);

/// The size of an existing regular file of at most kMaxFileBytes, else a refusal.
std::uintmax_t checked_file_size(const fs::path& file);

/// ".nii.gz" for a.NII.GZ, else the lower-case last extension (".nrrd").
std::string lower_extension(const fs::path& file);

/// Lower case, surrounding blanks removed.
std::string lower_trimmed(std::string_view text);

/// Whole-string number parses; false on anything else (no exceptions).
bool parse_int64(std::string_view text, std::int64_t& value);
bool parse_double(std::string_view text, double& value);
/// Blank-separated numbers; false when a token is not a number.
bool parse_doubles(std::string_view text, std::vector<double>& values);

enum class Scalar { u8, i8, u16, i16, u32, i32, f32, f64 };
std::size_t scalar_bytes(Scalar type);

/// A volume's placement as read from a header, before it is checked. Lengths in metres.
struct Geometry {
  std::array<std::int64_t, 3> dims{};
  std::array<double, 3> spacing{};
  std::array<double, 3> origin{};
  std::array<double, 9> direction{1, 0, 0, 0, 1, 0, 0, 0, 1};
};

/// The header field each part of the geometry came from, for the messages.
struct FieldNames {
  const char* dims;
  const char* spacing;
  const char* origin;
  const char* direction;
};

/// Spacing and unit directions from three axis vectors (columns[c] = world step along index
/// axis c, metres); a zero or non-finite vector is refused naming `field`.
void set_from_columns(const fs::path& file, const char* field, const std::array<std::array<double, 3>, 3>& columns,
                      Geometry& geometry);

/// LPS (or any frame with x and y reversed) to RAS: x and y of the origin and of every axis.
void flip_xy(Geometry& geometry);

/// Checks dims (positive, at most kMaxVoxels in all), spacing (finite, positive), origin
/// (finite) and direction (orthonormal within 1e-3); returns the volume without labels.
anatomy::LabelVolume checked_volume(const fs::path& file, const Geometry& geometry, const FieldNames& names);

/// Refuses (truncated) when `available` bytes cannot hold `needed`.
void check_raw_length(const fs::path& file, std::uintmax_t available, std::uintmax_t needed);
/// Refuses (truncated) when `compressed` bytes cannot inflate to `needed` (zlib's ratio is
/// at most 1032:1).
void check_compressed_length(const fs::path& file, std::uintmax_t compressed, std::uintmax_t needed);

/// Bytes from a file from an offset, raw or inflated (gzip or zlib, told apart by zlib).
class ByteSource {
 public:
  ByteSource(fs::path file, const fs::path& data, std::uintmax_t offset, bool compressed);
  ~ByteSource();
  ByteSource(const ByteSource&) = delete;
  ByteSource& operator=(const ByteSource&) = delete;
  /// Exactly n bytes, or a refusal naming `place` (truncated, corrupt compressed data).
  void read(unsigned char* out, std::size_t n, std::string_view place);
  void skip(std::uintmax_t n, std::string_view place);
  /// After the last voxel of compressed data: reads on to the end of the stream so that
  /// zlib checks its checksum (gzip CRC-32, zlib Adler-32); a mismatch or a missing end is
  /// refused. Nothing for raw data.
  void finish(std::string_view place);

 private:
  void inflate_into(unsigned char* out, std::size_t n, std::string_view place);
  fs::path file_;
  std::ifstream in_;
  bool compressed_;
  z_stream zs_{};
  std::vector<unsigned char> buffer_;
  bool ended_ = false;  // the compressed stream's end (and checksum) has been read
};

/// How the stored values become labels: their type, whether bytes are swapped, and NIfTI's
/// linear scaling (value = slope * stored + intercept) when slope is not 1 or intercept not 0.
struct Conversion {
  Scalar type = Scalar::u16;
  bool swap = false;
  double slope = 1.0;
  double intercept = 0.0;
};

/// Reads volume.voxel_count() values from `source` into volume.labels, refusing a value that
/// is not a label (not a whole number, or beyond a 32-bit integer) with its voxel index.
void read_labels(const fs::path& file, ByteSource& source, const Conversion& conversion, anatomy::LabelVolume& volume);

/// Converts `count` values in memory (native byte order) starting at voxel `first`.
void convert_labels(const fs::path& file, const unsigned char* data, std::size_t count, const Conversion& conversion,
                    std::size_t first, anatomy::LabelVolume& volume);

/// zlib (gzip = false) or gzip (gzip = true) compression of bytes, for the writers.
std::vector<unsigned char> deflate_bytes(const unsigned char* data, std::size_t n, bool gzip);

/// Writes bytes to a file or refuses naming it.
void write_file(const fs::path& file, const std::string& header, const unsigned char* data, std::size_t n);

/// "%.17g"-like shortest round-trip text of a number.
std::string number(double value);

// Readers and writers by format.
anatomy::LabelVolume read_nifti(const fs::path& file, bool gzip);
anatomy::LabelVolume read_nrrd(const fs::path& file);
anatomy::LabelVolume read_metaimage(const fs::path& file);
anatomy::LabelVolume read_vti(const fs::path& file);
void write_nifti(const fs::path& file, const anatomy::LabelVolume& volume, bool gzip);
void write_nrrd(const fs::path& file, const anatomy::LabelVolume& volume, bool detached);
void write_metaimage(const fs::path& file, const anatomy::LabelVolume& volume, bool detached);
void write_vti(const fs::path& file, const anatomy::LabelVolume& volume);
/// Refuses a volume whose labels or geometry are inconsistent before writing it.
void check_writable(const fs::path& file, const anatomy::LabelVolume& volume);

}  // namespace palpa::anatomy_io::detail
