// NRRD (.nrrd with attached data, .nhdr with a detached data file), header parsed and data
// decoded here: VTK 9.1 has no NRRD writer, and its reader is not used so that the sizes are
// checked before allocation and `space directions` / `space origin` are honoured.
#include <fmt/format.h>

#include <cmath>

#include "text_header.hpp"

namespace palpa::anatomy_io::detail {
namespace {

using Fields = std::vector<std::pair<std::string, std::string>>;

struct NrrdHeader {
  Fields fields;
  std::uintmax_t data_offset = 0;  // attached data: the byte after the blank line
  bool blank_line = false;
};

NrrdHeader parse_header(const fs::path& file, const std::string& text) {
  if (!text.starts_with("NRRD000")) fail(file, "magic", "does not start with NRRD000: not a NRRD file");
  NrrdHeader h;
  std::size_t start = text.find('\n');
  while (start != std::string::npos && start + 1 <= text.size()) {
    ++start;
    std::size_t end = text.find('\n', start);
    if (end == std::string::npos) end = text.size();
    std::string line = text.substr(start, end - start);
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty()) {
      h.blank_line = end < text.size();
      h.data_offset = end + 1;
      return h;
    }
    if (h.fields.size() > 1000) fail(file, "header", "more than 1000 lines");
    start = end < text.size() ? end : std::string::npos;
    if (line[0] == '#' || line.find(":=") != std::string::npos) continue;  // comments, key/value pairs
    const std::size_t colon = line.find(": ");
    if (colon == std::string::npos) fail(file, "header", fmt::format("line \"{}\" is not \"field: value\"", line));
    h.fields.emplace_back(lower_trimmed(line.substr(0, colon)), line.substr(colon + 2));
  }
  if (text.size() >= kMaxHeaderBytes) fail(file, "header", "no end within the first MiB");
  return h;
}

Scalar nrrd_type(const fs::path& file, const std::string& type) {
  const std::string t = lower_trimmed(type);
  if (t == "uchar" || t == "unsigned char" || t == "uint8" || t == "uint8_t") return Scalar::u8;
  if (t == "signed char" || t == "int8" || t == "int8_t") return Scalar::i8;
  if (t == "short" || t == "short int" || t == "signed short" || t == "signed short int" || t == "int16" ||
      t == "int16_t")
    return Scalar::i16;
  if (t == "ushort" || t == "unsigned short" || t == "unsigned short int" || t == "uint16" || t == "uint16_t")
    return Scalar::u16;
  if (t == "int" || t == "signed int" || t == "int32" || t == "int32_t") return Scalar::i32;
  if (t == "uint" || t == "unsigned int" || t == "uint32" || t == "uint32_t") return Scalar::u32;
  if (t == "float") return Scalar::f32;
  if (t == "double") return Scalar::f64;
  fail(file, "type", fmt::format("\"{}\" is not a label type (integers of 8 to 32 bits, float or double)", type));
}

const std::string& required(const fs::path& file, const Fields& fields, const char* key) {
  const std::string* value = find_field(fields, key);
  if (value == nullptr) fail(file, key, "missing");
  return *value;
}

// "(x,y,z)" vectors, blank-separated.
std::vector<std::array<double, 3>> vectors(const fs::path& file, const char* field, const std::string& text) {
  std::vector<std::array<double, 3>> out;
  std::size_t i = 0;
  while ((i = text.find_first_not_of(" \t", i)) != std::string::npos) {
    if (text[i] != '(') fail(file, field, fmt::format("\"{}\" is not a list of (x,y,z) vectors", text));
    const std::size_t close = text.find(')', i);
    if (close == std::string::npos || out.size() >= 3) fail(file, field, "not three (x,y,z) vectors");
    std::string inner = text.substr(i + 1, close - i - 1);
    for (char& c : inner) c = c == ',' ? ' ' : c;
    std::vector<double> v;
    if (!parse_doubles(inner, v) || v.size() != 3) fail(file, field, fmt::format("\"({})\" is not (x,y,z)", inner));
    out.push_back({v[0], v[1], v[2]});
    i = close + 1;
  }
  return out;
}

double units_of(const fs::path& file, const Fields& fields) {
  const std::string* units = find_field(fields, "space units");
  if (units == nullptr) return 1e-3;  // NRRD from 3D Slicer: millimetres
  const std::string u = lower_trimmed(*units);
  const std::string first = u.substr(0, u.find(' '));
  if (u != first + " " + first + " " + first) fail(file, "space units", "not the same unit on the three axes");
  if (first == "\"mm\"") return 1e-3;
  if (first == "\"m\"") return 1.0;
  if (first == "\"um\"") return 1e-6;
  fail(file, "space units", fmt::format("{} is not mm, m or um", *units));
}

// The world frame: +1 keeps x and y (RAS), -1 reverses both (LPS); LAS reverses x only.
std::array<double, 2> space_signs(const fs::path& file, const std::string& space) {
  const std::string s = lower_trimmed(space);
  if (s == "right-anterior-superior" || s == "ras" || s == "3d-right-handed") return {1, 1};
  if (s == "left-posterior-superior" || s == "lps") return {-1, -1};
  if (s == "left-anterior-superior" || s == "las") return {-1, 1};
  fail(file, "space", fmt::format("\"{}\" is not RAS, LPS, LAS or 3D-right-handed", space));
}

FieldNames nrrd_geometry(const fs::path& file, const Fields& fields, Geometry& g) {
  const double unit = units_of(file, fields);
  const std::string* space = find_field(fields, "space");
  const std::string* directions = find_field(fields, "space directions");
  if (space == nullptr && directions == nullptr) {  // no world frame: axis-aligned, spacings
    std::vector<double> s;
    if (!parse_doubles(required(file, fields, "spacings"), s) || s.size() != 3) fail(file, "spacings", "not 3 numbers");
    for (std::size_t a = 0; a < 3; ++a) g.spacing[a] = s[a] * unit;
    return {"sizes", "spacings", "space origin", "space directions"};
  }
  const auto signs = space == nullptr ? std::array<double, 2>{1, 1} : space_signs(file, *space);
  const auto columns = vectors(file, "space directions", required(file, fields, "space directions"));
  if (columns.size() != 3) fail(file, "space directions", "not three (x,y,z) vectors");
  std::array<std::array<double, 3>, 3> scaled{};
  for (std::size_t c = 0; c < 3; ++c) {
    for (std::size_t r = 0; r < 3; ++r) scaled[c][r] = columns[c][r] * unit * (r < 2 ? signs[r] : 1.0);
  }
  set_from_columns(file, "space directions", scaled, g);
  if (const std::string* origin = find_field(fields, "space origin")) {
    const auto o = vectors(file, "space origin", *origin);
    if (o.size() != 1) fail(file, "space origin", "not one (x,y,z) vector");
    for (std::size_t r = 0; r < 3; ++r) g.origin[r] = o[0][r] * unit * (r < 2 ? signs[r] : 1.0);
  }
  return {"sizes", "space directions", "space origin", "space directions"};
}

bool nrrd_compressed(const fs::path& file, const Fields& fields) {
  const std::string e = lower_trimmed(required(file, fields, "encoding"));
  if (e == "raw") return false;
  if (e == "gzip" || e == "gz") return true;
  fail(file, "encoding", fmt::format("\"{}\" is not raw or gzip", e));
}

}  // namespace

anatomy::LabelVolume read_nrrd(const fs::path& file) {
  const std::uintmax_t size = checked_file_size(file);
  const NrrdHeader h = parse_header(file, read_head(file, size));
  const Fields& f = h.fields;
  std::int64_t rank = 0;
  if (!parse_int64(required(file, f, "dimension"), rank) || rank != 3) fail(file, "dimension", "must be 3");
  Geometry g;
  std::vector<double> sizes;
  if (!parse_doubles(required(file, f, "sizes"), sizes) || sizes.size() != 3) fail(file, "sizes", "not 3 numbers");
  for (std::size_t a = 0; a < 3; ++a) {
    if (sizes[a] != std::floor(sizes[a]) || std::abs(sizes[a]) > 1e15) fail(file, "sizes", "not whole numbers");
    g.dims[a] = static_cast<std::int64_t>(sizes[a]);
  }
  const FieldNames names = nrrd_geometry(file, f, g);
  anatomy::LabelVolume volume = checked_volume(file, g, names);
  Conversion c;
  c.type = nrrd_type(file, required(file, f, "type"));
  if (const std::string* endian = find_field(f, "endian")) c.swap = lower_trimmed(*endian) == "big";
  const bool compressed = nrrd_compressed(file, f);
  const std::string* data_file = find_field(f, "data file");
  if (data_file == nullptr) data_file = find_field(f, "datafile");
  fs::path data = file;
  std::uintmax_t offset = h.data_offset;
  if (data_file != nullptr) {
    if (data_file->starts_with("LIST") || data_file->find('%') != std::string::npos) {
      fail(file, "data file", "lists of data files are not read; save as one .nrrd");
    }
    const std::size_t b = data_file->find_first_not_of(" \t");
    const std::size_t e = data_file->find_last_not_of(" \t");
    data = detached_path(file, "data file", b == std::string::npos ? std::string() : data_file->substr(b, e - b + 1));
    offset = 0;
  } else if (!h.blank_line) {
    fail(file, "header", "no blank line before the data (truncated)");
  }
  if (const std::string* lines = find_field(f, "line skip"); lines != nullptr && lower_trimmed(*lines) != "0") {
    fail(file, "line skip", "not read; use byte skip");
  }
  std::int64_t skip = 0;
  if (const std::string* s = find_field(f, "byte skip"); s != nullptr && (!parse_int64(*s, skip) || skip < -1)) {
    fail(file, "byte skip", "not a byte count or -1");
  }
  const std::uintmax_t data_size = data == file ? size : checked_file_size(data);
  const std::uintmax_t needed = volume.voxel_count() * scalar_bytes(c.type);
  if (skip == -1) {  // raw data at the end of the file
    if (compressed) fail(file, "byte skip", "-1 is for raw data only");
    check_raw_length(file, data_size - std::min(data_size, offset), needed);
    offset = data_size - needed;
    skip = 0;
  }
  if (compressed) {
    check_compressed_length(file, data_size - std::min(data_size, offset), needed);
  } else {
    check_raw_length(file, data_size - std::min(data_size, offset + static_cast<std::uintmax_t>(skip)), needed);
  }
  ByteSource source(file, data, compressed ? offset : offset + static_cast<std::uintmax_t>(skip), compressed);
  if (compressed) source.skip(static_cast<std::uintmax_t>(skip), "byte skip");
  read_labels(file, source, c, volume);
  return volume;
}

void write_nrrd(const fs::path& file, const anatomy::LabelVolume& v, bool detached) {
  check_writable(file, v);
  std::string header = "NRRD0004\n# written by Palpa (anatomy_io)\n";
  header += fmt::format("type: int\ndimension: 3\nspace: right-anterior-superior\nsizes: {} {} {}\n",
                        v.dims[0], v.dims[1], v.dims[2]);
  header += "space directions:";
  for (std::size_t c = 0; c < 3; ++c) {
    header += fmt::format(" ({},{},{})", number(v.direction[c] * v.spacing[c] * 1e3),
                          number(v.direction[3 + c] * v.spacing[c] * 1e3), number(v.direction[6 + c] * v.spacing[c] * 1e3));
  }
  header += "\nkinds: domain domain domain\nendian: little\n";
  header += fmt::format("space units: \"mm\" \"mm\" \"mm\"\nspace origin: ({},{},{})\n", number(v.origin[0] * 1e3),
                        number(v.origin[1] * 1e3), number(v.origin[2] * 1e3));
  const auto* bytes = reinterpret_cast<const unsigned char*>(v.labels.data());
  const std::size_t n = v.labels.size() * sizeof(anatomy::Label);
  if (detached) {
    const fs::path data = fs::path(file).replace_extension(".raw");
    header += fmt::format("encoding: raw\ndata file: {}\n", data.filename().string());
    write_file(data, std::string(), bytes, n);
    write_file(file, header, nullptr, 0);
    return;
  }
  header += "encoding: gzip\n\n";
  const auto packed = deflate_bytes(bytes, n, true);
  if (packed.empty()) fail(file, "write", "compression failed");
  write_file(file, header, packed.data(), packed.size());
}

}  // namespace palpa::anatomy_io::detail
