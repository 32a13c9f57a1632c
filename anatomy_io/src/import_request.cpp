#include "palpa/anatomy_io/import_request.hpp"

#include <algorithm>
#include <cctype>
#include <chrono>
#include <fstream>

#include <fmt/format.h>
#include <openssl/evp.h>

#include "palpa/anatomy/import_error.hpp"
#include "palpa/anatomy_io/anatomy_io.hpp"
#include "palpa/io/json_text.hpp"

namespace palpa::anatomy_io {

namespace {

using anatomy::ImportError;

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

bool ends_with(const std::string& s, const std::string& tail) {
  return s.size() >= tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}

std::string file_name(const std::filesystem::path& path) { return path.filename().string(); }

anatomy::ImportResult import_mesh(const ImportRequest& r, anatomy::Provenance& provenance) {
  if (!r.labels.empty() || r.table) throw ImportError("--labels: a mesh has no labels; give its tissue with --modulus PA");
  if (!(r.modulus > 0.0)) throw ImportError("--modulus: a mesh needs the tissue's Young's modulus in Pa (e.g. 3240)");
  if (r.support.empty() == !r.support_plane.has_value()) {
    throw ImportError("a mesh needs exactly one of --support SUPPORT_MESH and --support-plane \"nx,ny,nz,d\"");
  }
  const anatomy::ImportOptions options{r.rows, r.cols, "body"};
  const anatomy::TriangleMesh skin = read_mesh(r.input, r.metres_per_unit);
  if (r.support_plane) {
    const auto& p = *r.support_plane;
    return anatomy::import_closed_mesh(skin, Vec3(p[0], p[1], p[2]), p[3] * r.metres_per_unit, r.modulus, options,
                                       file_name(r.input));
  }
  if (input_kind(r.support) != InputKind::Mesh) {
    throw ImportError(fmt::format("--support: {}: not a mesh (.stl, .obj or .ply)", file_name(r.support)));
  }
  const anatomy::TriangleMesh support = read_mesh(r.support, r.metres_per_unit);
  provenance.support_source = file_name(r.support);
  provenance.support_sha256 = file_sha256(r.support);
  return anatomy::import_surfaces(skin, support, r.modulus, options, file_name(r.input), file_name(r.support));
}

// An in-memory table passes the checks parse_label_table makes of a file's entries.
void check_table(const anatomy::LabelTable& table) {
  if (table.labels.empty() || table.labels.size() > anatomy::kMaxLabels) {
    throw ImportError(fmt::format("{}: from 1 to {} labels", table.name, anatomy::kMaxLabels));
  }
  const auto span = static_cast<std::int64_t>(table.labels.rbegin()->first) - table.labels.begin()->first;
  if (span >= static_cast<std::int64_t>(anatomy::kMaxLabelSpan)) {
    throw ImportError(fmt::format("{}: labels from {} to {}: they may span at most {} values", table.name,
                                  table.labels.begin()->first, table.labels.rbegin()->first, anatomy::kMaxLabelSpan));
  }
  for (const auto& [label, entry] : table.labels) {
    if (entry.name.size() > anatomy::kMaxLabelNameLength) {
      throw ImportError(fmt::format("{}: label {}: a name of at most {} characters", table.name, label,
                                    anatomy::kMaxLabelNameLength));
    }
    const bool soft = anatomy::LabelTable::soft(entry.kind);
    if (soft && !(entry.modulus > 0.0 && entry.modulus <= io::CaseLimits::kMaxModulus)) {
      throw ImportError(fmt::format("{}: label {} ({}): {} needs a Young's modulus above 0 and at most {:g} Pa",
                                    table.name, label, entry.name, anatomy::to_string(entry.kind),
                                    io::CaseLimits::kMaxModulus));
    }
    if (!(entry.stiffening >= 0.0 && entry.stiffening <= io::CaseLimits::kMaxStiffening)) {
      throw ImportError(fmt::format("{}: label {} ({}): the stiffening must be in [0, {:g}]", table.name, label, entry.name,
                                    io::CaseLimits::kMaxStiffening));
    }
  }
}

anatomy::ImportResult import_volume(const ImportRequest& r, anatomy::Provenance& provenance) {
  if (r.labels.empty() && !r.table) throw ImportError("--labels: a label volume needs its label table: TABLE.json, victre or generic");
  if (!r.support.empty() || r.support_plane || r.modulus > 0.0) {
    throw ImportError("--support, --support-plane and --modulus are for meshes; a label volume's table gives its tissue");
  }
  if (r.table) check_table(*r.table);
  const anatomy::LabelTable table = r.table ? *r.table : load_label_table(r.labels);
  provenance.labels = table.name;
  const anatomy::LabelVolume volume = read_label_volume(r.input);
  return anatomy::import_label_volume(volume, table, {r.rows, r.cols, "body"}, file_name(r.input));
}

}  // namespace

InputKind input_kind(const std::filesystem::path& path) {
  const std::string name = lower(path.filename().string());
  for (const char* ext : {".nii", ".nii.gz", ".nrrd", ".nhdr", ".mhd", ".mha", ".vti"}) {
    if (ends_with(name, ext)) return InputKind::LabelVolume;
  }
  for (const char* ext : {".stl", ".obj", ".ply"}) {
    if (ends_with(name, ext)) return InputKind::Mesh;
  }
  return InputKind::Unknown;
}

anatomy::LabelTable load_label_table(const std::string& labels) {
  if (!ends_with(lower(labels), ".json")) return anatomy::builtin_label_table(labels);
  std::string text;
  if (const auto problem = io::read_text_file(labels, anatomy::kMaxLabelTableBytes, text)) {
    throw ImportError(fmt::format("--labels: {}: {}", std::filesystem::path(labels).filename().string(), problem->reason));
  }
  anatomy::LabelTable table = anatomy::parse_label_table(text, std::filesystem::path(labels).filename().string());
  return table;
}

std::string file_sha256(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw ImportError(fmt::format("{}: cannot be read", file_name(path)));
  EVP_MD_CTX* ctx = EVP_MD_CTX_new();
  if (ctx == nullptr || EVP_DigestInit_ex(ctx, EVP_sha256(), nullptr) != 1) {
    EVP_MD_CTX_free(ctx);
    throw ImportError("sha-256: libcrypto failed");
  }
  std::vector<char> chunk(1 << 20);
  while (in) {
    in.read(chunk.data(), static_cast<std::streamsize>(chunk.size()));
    EVP_DigestUpdate(ctx, chunk.data(), static_cast<std::size_t>(in.gcount()));
  }
  unsigned char digest[EVP_MAX_MD_SIZE];
  unsigned int length = 0;
  EVP_DigestFinal_ex(ctx, digest, &length);
  EVP_MD_CTX_free(ctx);
  std::string hex;
  for (unsigned int i = 0; i < length; ++i) hex += fmt::format("{:02x}", digest[i]);
  return hex;
}

ImportedCase import_anatomy(const ImportRequest& request) {
  const auto start = std::chrono::steady_clock::now();
  anatomy::Provenance provenance;
  provenance.source = file_name(request.input);
  provenance.command = request.command;
  ImportedCase out;
  switch (input_kind(request.input)) {
    case InputKind::LabelVolume:
      out.result = import_volume(request, provenance);
      break;
    case InputKind::Mesh:
      out.result = import_mesh(request, provenance);
      break;
    case InputKind::Unknown:
      throw ImportError(fmt::format("{}: unknown kind of file: a label volume (.nii, .nii.gz, .nrrd, .nhdr, .mhd, .mha, "
                                    ".vti) or a mesh (.stl, .obj, .ply)",
                                    provenance.source));
  }
  provenance.sha256 = file_sha256(request.input);
  const std::string title = request.title.empty() ? "Imported from " + provenance.source : request.title;
  out.file = anatomy::make_case(out.result, provenance, title, request.region);
  // "provenance" is a field other tools keep as written: naming the tool needs no revalidation.
  out.file.document["provenance"]["tool"] = request.tool;
  const double total = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  out.read_seconds = std::max(0.0, total - out.result.seconds);
  return out;
}

}  // namespace palpa::anatomy_io
