// MetaImage (.mha attached, .mhd with a detached data file), header parsed and data decoded
// here: vtkMetaImageReader in VTK 9.1 gives no direction (TransformMatrix is dropped), and the
// sizes must be checked before allocation. The world of a MetaImage is ITK's LPS: ITK reads
// TransformMatrix as the direction of index axis 0 in its first three numbers, of axis 1 in
// the next three, of axis 2 in the last (MetaImageIO: SetDirection(i, matrix[3 i .. 3 i + 2])),
// and Offset (or Position, Origin) as the position of voxel (0, 0, 0). x and y are negated
// to give RAS. ElementSpacing is in millimetres.
#include <fmt/format.h>

#include <cmath>

#include "text_header.hpp"

namespace palpa::anatomy_io::detail {
namespace {

using Fields = std::vector<std::pair<std::string, std::string>>;

struct MetaHeader {
  Fields fields;
  std::uintmax_t data_offset = 0;  // after the ElementDataFile line
};

MetaHeader parse_header(const fs::path& file, const std::string& text) {
  MetaHeader h;
  std::size_t start = 0;
  while (start < text.size()) {
    std::size_t end = text.find('\n', start);
    if (end == std::string::npos) end = text.size();
    std::string line = text.substr(start, end - start);
    start = end + 1;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (lower_trimmed(line).empty()) continue;
    const std::size_t eq = line.find('=');
    if (eq == std::string::npos) fail(file, "header", fmt::format("line \"{}\" is not \"Key = Value\"", line.substr(0, 60)));
    if (h.fields.size() > 200) fail(file, "header", "more than 200 lines");
    std::string key = lower_trimmed(line.substr(0, eq));
    const std::string value = line.substr(eq + 1);
    const std::size_t b = value.find_first_not_of(" \t");
    const std::size_t e = value.find_last_not_of(" \t");
    h.fields.emplace_back(key, b == std::string::npos ? std::string() : value.substr(b, e - b + 1));
    if (key == "elementdatafile") {  // always the last field; the data follows it
      h.data_offset = std::min<std::uintmax_t>(start, text.size());
      return h;
    }
  }
  if (h.fields.empty() || (h.fields.front().first != "objecttype" && h.fields.front().first != "ndims")) {
    fail(file, "header", "not a MetaImage header");
  }
  fail(file, "ElementDataFile", "missing");
}

Scalar meta_type(const fs::path& file, const std::string& type) {
  const std::string t = lower_trimmed(type);
  if (t == "met_uchar") return Scalar::u8;
  if (t == "met_char") return Scalar::i8;
  if (t == "met_ushort") return Scalar::u16;
  if (t == "met_short") return Scalar::i16;
  if (t == "met_uint") return Scalar::u32;
  if (t == "met_int") return Scalar::i32;
  if (t == "met_float") return Scalar::f32;
  if (t == "met_double") return Scalar::f64;
  fail(file, "ElementType", fmt::format("{} is not a label type (integers of 8 to 32 bits, float or double)", type));
}

const std::string* any_of(const Fields& f, std::initializer_list<const char*> keys) {
  for (const char* key : keys) {
    if (const std::string* v = find_field(f, key)) return v;
  }
  return nullptr;
}

std::vector<double> numbers(const fs::path& file, const char* field, const std::string* text, std::size_t count) {
  std::vector<double> v;
  if (text == nullptr) fail(file, field, "missing");
  if (!parse_doubles(*text, v) || v.size() != count) fail(file, field, fmt::format("not {} numbers", count));
  return v;
}

bool is_true(const std::string* text) { return text != nullptr && lower_trimmed(*text) == "true"; }

Geometry meta_geometry(const fs::path& file, const Fields& f) {
  Geometry g;
  const auto dims = numbers(file, "DimSize", find_field(f, "dimsize"), 3);
  for (std::size_t a = 0; a < 3; ++a) {
    if (dims[a] != std::floor(dims[a]) || std::abs(dims[a]) > 1e15) fail(file, "DimSize", "not whole numbers");
    g.dims[a] = static_cast<std::int64_t>(dims[a]);
  }
  const std::string* spacing_text = any_of(f, {"elementspacing", "elementsize"});
  const auto spacing = spacing_text == nullptr ? std::vector<double>{1, 1, 1} : numbers(file, "ElementSpacing", spacing_text, 3);
  std::vector<double> matrix{1, 0, 0, 0, 1, 0, 0, 0, 1};
  if (const std::string* m = any_of(f, {"transformmatrix", "rotation", "orientation"})) {
    matrix = numbers(file, "TransformMatrix", m, 9);
  }
  std::vector<double> offset{0, 0, 0};
  if (const std::string* o = any_of(f, {"offset", "position", "origin"})) offset = numbers(file, "Offset", o, 3);
  std::array<std::array<double, 3>, 3> columns{};
  for (std::size_t c = 0; c < 3; ++c) {
    const double length = std::sqrt(matrix[3 * c] * matrix[3 * c] + matrix[3 * c + 1] * matrix[3 * c + 1] +
                                     matrix[3 * c + 2] * matrix[3 * c + 2]);
    if (!(std::abs(length - 1.0) <= 1e-3)) {
      fail(file, "TransformMatrix", fmt::format("axis {} has length {:.6g}, not 1: not orthonormal", c, length));
    }
    if (!std::isfinite(spacing[c]) || !(spacing[c] > 0)) {
      fail(file, "ElementSpacing", fmt::format("spacing {} along axis {} must be finite and positive", spacing[c], c));
    }
    for (std::size_t r = 0; r < 3; ++r) columns[c][r] = matrix[3 * c + r] * spacing[c] * 1e-3;
  }
  set_from_columns(file, "TransformMatrix", columns, g);
  for (std::size_t r = 0; r < 3; ++r) g.origin[r] = offset[r] * 1e-3;
  flip_xy(g);  // LPS to RAS
  return g;
}

}  // namespace

anatomy::LabelVolume read_metaimage(const fs::path& file) {
  const std::uintmax_t size = checked_file_size(file);
  const MetaHeader h = parse_header(file, read_head(file, size));
  const Fields& f = h.fields;
  if (const std::string* n = find_field(f, "ndims"); n == nullptr || lower_trimmed(*n) != "3") {
    fail(file, "NDims", "must be 3");
  }
  anatomy::LabelVolume volume =
      checked_volume(file, meta_geometry(file, f), {"DimSize", "ElementSpacing", "Offset", "TransformMatrix"});
  if (const std::string* ch = find_field(f, "elementnumberofchannels"); ch != nullptr && lower_trimmed(*ch) != "1") {
    fail(file, "ElementNumberOfChannels", "must be 1 for a label volume");
  }
  if (const std::string* b = find_field(f, "binarydata"); b != nullptr && !is_true(b)) {
    fail(file, "BinaryData", "ASCII MetaImage data is not read");
  }
  Conversion c;
  c.type = meta_type(file, *any_of(f, {"elementtype"}) );
  c.swap = is_true(any_of(f, {"binarydatabyteordermsb", "elementbyteordermsb"}));
  const bool compressed = is_true(find_field(f, "compresseddata"));
  const std::string& name = *find_field(f, "elementdatafile");
  fs::path data = file;
  std::uintmax_t offset = h.data_offset;
  if (lower_trimmed(name) != "local") {
    if (lower_trimmed(name).starts_with("list") || name.find('%') != std::string::npos) {
      fail(file, "ElementDataFile", "lists of data files are not read; save as one .mha");
    }
    data = detached_path(file, "ElementDataFile", name);
    offset = 0;
  }
  const std::uintmax_t data_size = data == file ? size : checked_file_size(data);
  const std::uintmax_t needed = volume.voxel_count() * scalar_bytes(c.type);
  std::int64_t header_size = 0;
  if (const std::string* hs = find_field(f, "headersize"); hs != nullptr && (!parse_int64(*hs, header_size) || header_size < -1)) {
    fail(file, "HeaderSize", "not a byte count or -1");
  }
  if (header_size == -1 && !compressed) {
    check_raw_length(file, data_size - std::min(data_size, offset), needed);
    offset = data_size - needed;
  } else if (header_size > 0) {
    offset += static_cast<std::uintmax_t>(header_size);
  }
  const std::uintmax_t available = data_size - std::min(data_size, offset);
  if (compressed) {
    check_compressed_length(file, available, needed);
  } else {
    check_raw_length(file, available, needed);
  }
  ByteSource source(file, data, offset, compressed);
  read_labels(file, source, c, volume);
  return volume;
}

void write_metaimage(const fs::path& file, const anatomy::LabelVolume& v, bool detached) {
  check_writable(file, v);
  const auto& d = v.direction;
  std::string header = "ObjectType = Image\nNDims = 3\nBinaryData = True\nBinaryDataByteOrderMSB = False\n";
  const auto* bytes = reinterpret_cast<const unsigned char*>(v.labels.data());
  const std::size_t n = v.labels.size() * sizeof(anatomy::Label);
  std::vector<unsigned char> packed;
  if (!detached) {
    packed = deflate_bytes(bytes, n, false);
    if (packed.empty()) fail(file, "write", "compression failed");
    header += fmt::format("CompressedData = True\nCompressedDataSize = {}\n", packed.size());
  } else {
    header += "CompressedData = False\n";
  }
  // LPS: x and y negated; TransformMatrix lists the axes' directions one after the other.
  header += fmt::format("TransformMatrix = {} {} {} {} {} {} {} {} {}\n", number(-d[0]), number(-d[3]), number(d[6]),
                        number(-d[1]), number(-d[4]), number(d[7]), number(-d[2]), number(-d[5]), number(d[8]));
  header += fmt::format("Offset = {} {} {}\nCenterOfRotation = 0 0 0\n", number(-v.origin[0] * 1e3),
                        number(-v.origin[1] * 1e3), number(v.origin[2] * 1e3));
  header += fmt::format("ElementSpacing = {} {} {}\nDimSize = {} {} {}\nElementType = MET_INT\n",
                        number(v.spacing[0] * 1e3), number(v.spacing[1] * 1e3), number(v.spacing[2] * 1e3), v.dims[0],
                        v.dims[1], v.dims[2]);
  if (detached) {
    const fs::path data = fs::path(file).replace_extension(".raw");
    header += fmt::format("ElementDataFile = {}\n", data.filename().string());
    write_file(data, std::string(), bytes, n);
    write_file(file, header, nullptr, 0);
    return;
  }
  header += "ElementDataFile = LOCAL\n";
  write_file(file, header, packed.data(), packed.size());
}

}  // namespace palpa::anatomy_io::detail
