#include "palpa/io/case_file.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <set>

#include <fmt/format.h>

#include "palpa/io/json_text.hpp"
#include "palpa/mat/layer_stiffness.hpp"
#include "palpa/io/thresholds.hpp"
#include "palpa/io/training.hpp"

namespace palpa::io {
namespace {

using nlohmann::json;
using L = CaseLimits;

// Length in characters (UTF-8 code points), as the schema's maxLength counts.
std::size_t utf8_length(const std::string& s) {
  std::size_t n = 0;
  for (char c : s) n += (static_cast<unsigned char>(c) & 0xC0u) != 0x80u ? 1u : 0u;
  return n;
}

// A JSON value for an error message, cut short so one problem stays one readable line.
std::string brief(const json& value) {
  std::string s = value.dump(-1, ' ', true, json::error_handler_t::replace);
  if (s.size() > 40) s = s.substr(0, 37) + "...";
  return s;
}

class Validator {
 public:
  void add(std::string where, std::string reason) {
    if (problems_.size() < L::kMaxProblems) {
      problems_.push_back({std::move(where), std::move(reason)});
    } else {
      ++dropped_;
    }
  }
  bool ok() const { return problems_.empty(); }
  std::vector<Problem> take() {
    if (dropped_ > 0) problems_.push_back({"/", fmt::format("{} more problems not shown", dropped_)});
    return std::move(problems_);
  }
  std::size_t count() const { return problems_.size() + dropped_; }

 private:
  std::vector<Problem> problems_;
  std::size_t dropped_ = 0;
};

struct Range {
  double lo;
  double hi;
  bool lo_open;  // true: lo itself is not allowed
  const char* unit;
};

// Reads one number, checking type, finiteness and range. Returns false (with a problem) if bad.
bool read_number(const json& value, const std::string& where, const char* name, Range range, Validator& v,
                 double& out) {
  if (!value.is_number()) {
    v.add(where, std::string(name) + " must be a number, not " + value.type_name());
    return false;
  }
  out = value.get<double>();
  if (!std::isfinite(out)) {
    v.add(where, std::string(name) + " is not finite");
    return false;
  }
  if (range.lo == 0.0 && out < 0.0) {
    v.add(where, fmt::format("negative {} {:.6g} {}", name, out, range.unit));
    return false;
  }
  if (out < range.lo || (range.lo_open && out == range.lo) || out > range.hi) {
    v.add(where, fmt::format("{} {:.6g} {} is outside {}{:.6g}, {:.6g}] {}", name, out, range.unit,
                             range.lo_open ? "(" : "[", range.lo, range.hi, range.unit));
    return false;
  }
  return true;
}

bool read_int(const json& obj, const std::string& base, const char* key, int lo, int hi, Validator& v, int& out) {
  const std::string where = base + "/" + key;
  if (!obj.contains(key)) {
    v.add(base, std::string("missing \"") + key + "\"");
    return false;
  }
  const json& value = obj[key];
  // 5.0 counts as the integer 5, as in JSON Schema; 5.5 does not.
  const bool integral = value.is_number_integer() ||
                        (value.is_number_float() && std::isfinite(value.get<double>()) &&
                         std::trunc(value.get<double>()) == value.get<double>());
  if (!integral) {
    v.add(where, std::string(key) + " must be an integer, not " +
                     (value.is_number() ? std::string("a fraction") : std::string(value.type_name())));
    return false;
  }
  const auto big = value.is_number_unsigned() ? static_cast<long double>(value.get<std::uint64_t>())
                   : value.is_number_integer() ? static_cast<long double>(value.get<std::int64_t>())
                                               : static_cast<long double>(value.get<double>());
  if (big < lo || big > hi) {
    v.add(where, fmt::format("{} {} is outside [{}, {}]", key, brief(value), lo, hi));
    return false;
  }
  out = static_cast<int>(big);
  return true;
}

// A per-point array of `count` numbers in `range`; an empty result means absent or bad.
bool read_channel(const json& body, const std::string& base, const char* key, std::size_t count, Range range,
                  bool required, Validator& v, std::vector<double>& out) {
  const std::string where = base + "/" + key;
  if (!body.contains(key)) {
    if (required) v.add(base, std::string("missing \"") + key + "\"");
    return !required;
  }
  const json& arr = body[key];
  if (!arr.is_array()) {
    v.add(where, fmt::format("{} must be an array of {} numbers", key, count));
    return false;
  }
  if (arr.size() != count) {
    v.add(where, fmt::format("{} has {} values, expected rows*cols = {}", key, arr.size(), count));
    return false;
  }
  out.resize(count);
  bool good = true;
  for (std::size_t k = 0; k < count; ++k) {
    good = read_number(arr[k], fmt::format("{}/{}", where, k), key, range, v, out[k]) && good;
  }
  return good;
}

bool read_medial(const json& body, const std::string& base, std::size_t count, Validator& v,
                 std::vector<std::array<double, 3>>& out) {
  const std::string where = base + "/medial";
  if (!body.contains("medial")) {
    v.add(base, "missing \"medial\"");
    return false;
  }
  const json& arr = body["medial"];
  if (!arr.is_array()) {
    v.add(where, "medial must be an array of [x, y, z] points");
    return false;
  }
  if (arr.size() != count) {
    v.add(where, fmt::format("medial has {} points, expected rows*cols = {}", arr.size(), count));
    return false;
  }
  out.resize(count);
  const Range range{-L::kMaxCoordinate, L::kMaxCoordinate, false, "m"};
  bool good = true;
  for (std::size_t k = 0; k < count; ++k) {
    const std::string pk = fmt::format("{}/{}", where, k);
    if (!arr[k].is_array() || arr[k].size() != 3) {
      v.add(pk, "a medial point must be an array of 3 numbers [x, y, z]");
      good = false;
      continue;
    }
    for (std::size_t c = 0; c < 3; ++c) {
      good = read_number(arr[k][c], fmt::format("{}/{}", pk, c), "coordinate", range, v, out[k][c]) && good;
    }
  }
  return good;
}

// The paper's closure condition: r = 0 on the grid boundary, so the contours meet there.
void check_boundary_radius(const mat::BodyGrid& g, const std::string& base, Validator& v) {
  for (int i = 0; i < g.rows; ++i) {
    for (int j = 0; j < g.cols; ++j) {
      if (i != 0 && i != g.rows - 1 && j != 0 && j != g.cols - 1) continue;
      const std::size_t k = static_cast<std::size_t>(i * g.cols + j);
      if (g.radius[k] != 0.0) {
        v.add(fmt::format("{}/radius/{}", base, k),
              fmt::format("radius {:.6g} m on the grid boundary (point {}, {}); it must be 0 there so the top and "
                          "bottom contours close",
                          g.radius[k], i, j));
      }
    }
  }
}

// Bodies of absurd size or shape cost scoring and display work out of all proportion to
// what a person palpates (a 200 m plane, a point pulled 50 m out): not a plausible body.
void check_plausible(const mat::BodyGrid& g, const std::string& base, bool medial_ok, bool radius_ok, Validator& v) {
  if (medial_ok) {
    for (std::size_t c = 0; c < 3; ++c) {
      double lo = g.medial[0][c], hi = lo;
      for (const auto& p : g.medial) {
        lo = std::min(lo, p[c]);
        hi = std::max(hi, p[c]);
      }
      if (hi - lo > L::kMaxBodyExtent) {
        v.add(base + "/medial",
              fmt::format("not a plausible body: its skeleton spans {:.6g} m along {} (at most {:.6g} m)", hi - lo,
                          static_cast<char>('x' + c), L::kMaxBodyExtent));
      }
    }
    const auto spacing = [&](int i, int j, int i2, int j2) {
      const auto& a = g.medial[static_cast<std::size_t>(i * g.cols + j)];
      const auto& b = g.medial[static_cast<std::size_t>(i2 * g.cols + j2)];
      return std::hypot(a[0] - b[0], a[1] - b[1], a[2] - b[2]);
    };
    for (int i = 0; i < g.rows; ++i) {
      for (int j = 0; j < g.cols; ++j) {
        const double far = std::max(i + 1 < g.rows ? spacing(i, j, i + 1, j) : 0.0,
                                    j + 1 < g.cols ? spacing(i, j, i, j + 1) : 0.0);
        if (far > L::kMaxPointSpacing) {
          v.add(fmt::format("{}/medial/{}", base, i * g.cols + j),
                fmt::format("not a plausible body: a neighbouring skeleton point is {:.6g} m away (at most {:.6g} m)",
                            far, L::kMaxPointSpacing));
          return;
        }
      }
    }
  }
  if (radius_ok) {
    const auto thickest = std::max_element(g.radius.begin(), g.radius.end());
    if (thickest != g.radius.end() && 2.0 * *thickest > L::kMaxBodyThickness) {
      v.add(fmt::format("{}/radius/{}", base, thickest - g.radius.begin()),
            fmt::format("not a plausible body: radius {:.6g} m makes it {:.6g} m thick (at most {:.6g} m)", *thickest,
                        2.0 * *thickest, L::kMaxBodyThickness));
    }
  }
}

// Coincident neighbours make the interpolation singular, except inside a pole: a boundary
// row or column that collapses to one point as a whole (the grid's edge at a dome's apex,
// where the radius is 0). An interior row cannot be a pole: the skeleton's normal would
// flip across it and the contours would pass through one another.
void check_coincident(const mat::BodyGrid& g, const std::string& base, Validator& v) {
  auto at = [&](int i, int j) { return g.medial[static_cast<std::size_t>(i * g.cols + j)]; };
  std::vector<bool> pole_row(static_cast<std::size_t>(g.rows), true);
  std::vector<bool> pole_col(static_cast<std::size_t>(g.cols), true);
  for (int i = 0; i < g.rows; ++i) {
    const bool boundary = i == 0 || i == g.rows - 1;
    for (int j = 1; j < g.cols; ++j)
      if (!boundary || at(i, j) != at(i, 0)) pole_row[static_cast<std::size_t>(i)] = false;
  }
  for (int j = 0; j < g.cols; ++j) {
    const bool boundary = j == 0 || j == g.cols - 1;
    for (int i = 1; i < g.rows; ++i)
      if (!boundary || at(i, j) != at(0, j)) pole_col[static_cast<std::size_t>(j)] = false;
  }

  auto report = [&](int i, int j, int i0, int j0) {
    v.add(fmt::format("{}/medial/{}", base, i * g.cols + j),
          fmt::format("skeleton point ({}, {}) coincides with its neighbour ({}, {})", i, j, i0, j0));
  };
  for (int i = 0; i < g.rows; ++i) {
    for (int j = 0; j < g.cols; ++j) {
      if (i > 0 && !pole_col[static_cast<std::size_t>(j)] && at(i, j) == at(i - 1, j)) report(i, j, i - 1, j);
      if (j > 0 && !pole_row[static_cast<std::size_t>(i)] && at(i, j) == at(i, j - 1)) report(i, j, i, j - 1);
    }
  }
}

// "support": what the body rests on (docs/case-format.md); absent means "free".
void read_support(const json& body, const std::string& base, Validator& v, mat::Support& support) {
  if (!body.contains("support")) return;
  const json& s = body["support"];
  if (s == "bottom") {
    support = mat::Support::Bottom;
  } else if (s != "free") {
    v.add(base + "/support", "support must be \"free\" or \"bottom\", not " + brief(s));
  }
}

// "force_model": "paper" or "calibrated" (docs/case-format.md); absent: calibrated for a
// body given by its modulus, paper for one given in N/m.
void read_force_model(const json& body, const std::string& base, Validator& v, mat::BodyGrid& g) {
  g.force_model = g.modulus.empty() ? mat::ForceModel::Paper : mat::ForceModel::Calibrated;
  if (!body.contains("force_model")) return;
  const json& m = body["force_model"];
  if (m == "paper") {
    g.force_model = mat::ForceModel::Paper;
  } else if (m == "calibrated") {
    g.force_model = mat::ForceModel::Calibrated;
  } else {
    v.add(base + "/force_model", "force_model must be \"paper\" or \"calibrated\", not " + brief(m));
  }
}

// The tissue's material: "stiffness" in N/m per point (the paper's), or "modulus" in Pa
// per point with an optional "poisson", from which the stiffness under a fingertip pad is
// derived over the local thickness 2R (mat/layer_stiffness.hpp). Exactly one of the two.
void read_tissue(const json& body, const std::string& base, std::size_t n, bool radius_ok, Validator& v,
                 mat::BodyGrid& g) {
  const bool by_stiffness = body.contains("stiffness");
  const bool by_modulus = body.contains("modulus");
  if (by_stiffness && by_modulus) {
    v.add(base + "/modulus", "give the tissue as \"stiffness\" (N/m) or as \"modulus\" (Pa), not both");
    return;
  }
  if (!by_modulus) {
    if (body.contains("stiffening")) {
      v.add(base + "/stiffening", "stiffening needs the tissue given by \"modulus\" (Pa), not \"stiffness\"");
    }
    if (!by_stiffness) v.add(base, "missing \"stiffness\" (N/m) or \"modulus\" (Pa)");
    else read_channel(body, base, "stiffness", n, {0.0, L::kMaxStiffness, false, "N/m"}, true, v, g.stiffness);
    read_force_model(body, base, v, g);
    return;
  }
  bool good = read_channel(body, base, "modulus", n, {0.0, L::kMaxModulus, false, "Pa"}, true, v, g.modulus);
  if (body.contains("poisson")) {
    good = read_number(body["poisson"], base + "/poisson", "poisson", {0.0, L::kMaxPoisson, false, "(ratio)"}, v,
                       g.poisson) && good;
  }
  if (body.contains("stiffening")) {
    good = read_number(body["stiffening"], base + "/stiffening", "stiffening",
                       {0.0, L::kMaxStiffening, false, "(per unit strain)"}, v, g.stiffening) && good;
  }
  read_force_model(body, base, v, g);
  if (!good || !radius_ok) return;
  g.stiffness = mat::layer_stiffness_field(g.modulus, g.radius, g.poisson);
}

void read_body(const json& body, std::size_t index, std::set<std::string>& ids, Validator& v,
               std::vector<mat::BodyGrid>& bodies) {
  const std::string base = fmt::format("/bodies/{}", index);
  if (!body.is_object()) {
    v.add(base, "a body must be an object");
    return;
  }
  const std::size_t before = v.count();
  mat::BodyGrid g;
  if (!body.contains("id")) {
    v.add(base, "missing \"id\"");
  } else if (!body["id"].is_string() || body["id"].get_ref<const std::string&>().empty()) {
    v.add(base + "/id", "id must be a non-empty string");
  } else if (utf8_length(body["id"].get_ref<const std::string&>()) > L::kMaxIdLength) {
    v.add(base + "/id", fmt::format("id is longer than {} characters", L::kMaxIdLength));
  } else if (std::any_of(body["id"].get_ref<const std::string&>().begin(), body["id"].get_ref<const std::string&>().end(),
                         [](char c) { return static_cast<unsigned char>(c) < 0x20 || c == 0x7f; })) {
    v.add(base + "/id", "id must not contain control characters (ids appear in messages and reports)");
  } else {
    g.id = body["id"].get<std::string>();
    if (!ids.insert(g.id).second) v.add(base + "/id", "duplicate body id \"" + g.id + "\"");
  }

  read_support(body, base, v, g.support);
  const bool rows_ok = read_int(body, base, "rows", L::kMinGrid, L::kMaxGrid, v, g.rows);
  const bool cols_ok = read_int(body, base, "cols", L::kMinGrid, L::kMaxGrid, v, g.cols);
  if (!rows_ok || !cols_ok) return;  // the per-point arrays cannot be checked without a size
  const auto n = static_cast<std::size_t>(g.rows * g.cols);
  const bool medial_ok = read_medial(body, base, n, v, g.medial);
  const bool radius_ok = read_channel(body, base, "radius", n, {0.0, L::kMaxRadius, false, "m"}, true, v, g.radius);
  read_tissue(body, base, n, radius_ok, v, g);
  read_channel(body, base, "damping", n, {0.0, L::kMaxDamping, false, "N s/m"}, false, v, g.damping);
  read_channel(body, base, "mass", n, {0.0, L::kMaxMass, true, "kg"}, false, v, g.mass);
  if (radius_ok) check_boundary_radius(g, base, v);
  check_plausible(g, base, medial_ok, radius_ok, v);
  if (medial_ok) check_coincident(g, base, v);
  if (v.count() == before) bodies.push_back(std::move(g));
}

// A tumour's randomization rule: { "u": [u0, u1], "v": [v0, v1], "depth": [d0, d1] }, each
// range within [0, 1] and ordered. Its keys are Palpa's own, so unknown ones are typos.
void read_placement(const json& p, const std::string& base, Validator& v) {
  if (!p.is_object()) {
    v.add(base, std::string("placement must be an object {\"u\", \"v\", \"depth\"}, not ") + p.type_name());
    return;
  }
  for (const auto& [key, value] : p.items()) {
    if (key != "u" && key != "v" && key != "depth") {
      v.add(base + "/" + key, "unknown placement field " + brief(key) + " (expected u, v, depth)");
    }
  }
  for (const char* key : {"u", "v", "depth"}) {
    const std::string where = base + "/" + key;
    if (!p.contains(key)) {
      v.add(base, std::string("missing \"") + key + "\"");
      continue;
    }
    const json& range = p[key];
    if (!range.is_array() || range.size() != 2) {
      v.add(where, std::string(key) + " must be an array of 2 numbers [low, high]");
      continue;
    }
    double lo = 0.0, hi = 0.0;
    const Range unit{0.0, 1.0, false, "(fraction)"};
    const bool lo_ok = read_number(range[0], where + "/0", key, unit, v, lo);
    const bool hi_ok = read_number(range[1], where + "/1", key, unit, v, hi);
    if (lo_ok && hi_ok && lo > hi) v.add(where, fmt::format("{} range [{:.6g}, {:.6g}] is reversed", key, lo, hi));
  }
}

// A tumour: { "body", "center", "radius", "stiffness" } (m, m, N/m) and an optional
// "placement"; extra fields allowed.
// Whether it lies inside its body needs the fitted body: scene::Scene::build checks that.
void read_tumour(const json& t, std::size_t index, const std::set<std::string>& ids, bool bodies_ok, Validator& v,
                 std::vector<mat::Tumour>& out) {
  const std::string base = fmt::format("/tumors/{}", index);
  if (!t.is_object()) {
    v.add(base, "a tumour must be an object");
    return;
  }
  const std::size_t before = v.count();
  mat::Tumour tumour;
  if (!t.contains("body")) {
    v.add(base, "missing \"body\" (the id of the body that holds the tumour)");
  } else if (!t["body"].is_string()) {
    v.add(base + "/body", "body must be a body id (a string)");
  } else {
    tumour.body = t["body"].get<std::string>();
    if (bodies_ok && !ids.contains(tumour.body)) {
      std::string known;
      for (const auto& id : ids) known += (known.empty() ? "" : ", ") + id;
      v.add(base + "/body", "unknown body " + brief(t["body"]) + " (bodies: " + known + ")");
    }
  }
  if (!t.contains("center")) {
    v.add(base, "missing \"center\"");
  } else if (!t["center"].is_array() || t["center"].size() != 3) {
    v.add(base + "/center", "center must be an array of 3 numbers [x, y, z]");
  } else {
    for (std::size_t c = 0; c < 3; ++c) {
      read_number(t["center"][c], fmt::format("{}/center/{}", base, c), "coordinate",
                  {-L::kMaxCoordinate, L::kMaxCoordinate, false, "m"}, v, tumour.center[c]);
    }
  }
  if (!t.contains("radius")) {
    v.add(base, "missing \"radius\"");
  } else {
    read_number(t["radius"], base + "/radius", "radius", {0.0, L::kMaxTumourRadius, true, "m"}, v, tumour.radius);
  }
  // Its material: "stiffness" in N/m (the spring model) or "modulus" in Pa (the contrast
  // model, for a tumour in a body given by its modulus; Scene::build checks that).
  if (t.contains("stiffness") && t.contains("modulus")) {
    v.add(base + "/modulus", "give the tumour as \"stiffness\" (N/m) or as \"modulus\" (Pa), not both");
  } else if (t.contains("modulus")) {
    read_number(t["modulus"], base + "/modulus", "modulus", {0.0, L::kMaxModulus, true, "Pa"}, v, tumour.modulus);
    if (t.contains("stiffening")) {
      read_number(t["stiffening"], base + "/stiffening", "stiffening", {0.0, L::kMaxStiffening, false, "(per unit strain)"},
                  v, tumour.stiffening);
    }
  } else if (t.contains("stiffening")) {
    v.add(base + "/stiffening", "stiffening needs the tumour given by \"modulus\" (Pa), not \"stiffness\"");
  } else if (!t.contains("stiffness")) {
    v.add(base, "missing \"stiffness\" (N/m) or \"modulus\" (Pa)");
  } else {
    read_number(t["stiffness"], base + "/stiffness", "stiffness", {0.0, L::kMaxStiffness, false, "N/m"}, v,
                tumour.stiffness);
  }
  if (t.contains("placement")) read_placement(t["placement"], base + "/placement", v);
  if (v.count() == before) out.push_back(std::move(tumour));
}

// "provenance" (docs/case-format.md, "Provenance"): where an imported case came from, as
// palpa-cli import wrote it. Kept as written; its text fields are checked, since tools show them.
void check_provenance(const json& doc, Validator& v) {
  if (!doc.contains("provenance")) return;
  const json& p = doc["provenance"];
  if (!p.is_object()) {
    v.add("/provenance", std::string("provenance must be an object, not ") + p.type_name());
    return;
  }
  for (const char* key : {"tool", "palpa_version", "source", "support_source", "labels", "options", "grid"}) {
    if (p.contains(key) && (!p[key].is_string() || utf8_length(p[key].get_ref<const std::string&>()) > 1024)) {
      v.add(std::string("/provenance/") + key, std::string(key) + " must be a string of at most 1024 characters");
    }
  }
  for (const char* key : {"sha256", "support_sha256"}) {
    const bool hex = p.contains(key) && p[key].is_string() && p[key].get_ref<const std::string&>().size() == 64 &&
                     p[key].get_ref<const std::string&>().find_first_not_of("0123456789abcdef") == std::string::npos;
    if (p.contains(key) && !hex) v.add(std::string("/provenance/") + key, std::string(key) + " must be 64 lower-case hex digits");
  }
}

CaseFile validate(json doc, Validator& v) {
  CaseFile out;
  if (!doc.is_object()) {
    v.add("/", std::string("a case must be a JSON object, not ") + doc.type_name());
    return out;
  }
  if (!doc.contains("format")) {
    v.add("/", "missing \"format\" (expected \"palpa-case\")");
  } else if (doc["format"] != "palpa-case") {
    v.add("/format", "unknown format " + brief(doc["format"]) + " (expected \"palpa-case\")");
  }
  if (!doc.contains("version")) {
    v.add("/", "missing \"version\" (expected 1)");
  } else if (!doc["version"].is_number_integer() || doc["version"] != 1) {
    v.add("/version", "unsupported version " + brief(doc["version"]) + " (this Palpa reads version 1)");
  }
  if (!doc.contains("title")) {
    v.add("/", "missing \"title\"");
  } else if (!doc["title"].is_string()) {
    v.add("/title", std::string("title must be a string, not ") + doc["title"].type_name());
  } else if (utf8_length(doc["title"].get_ref<const std::string&>()) > L::kMaxTitleLength) {
    v.add("/title", fmt::format("title is longer than {} characters", L::kMaxTitleLength));
  } else {
    out.title = doc["title"].get<std::string>();
  }
  // Optional: what the case is about, for whoever picks it (the instructor window edits it).
  if (doc.contains("description") && !doc["description"].is_string()) {
    v.add("/description", std::string("description must be a string, not ") + doc["description"].type_name());
  } else if (doc.contains("description") &&
             utf8_length(doc["description"].get_ref<const std::string&>()) > L::kMaxDescriptionLength) {
    v.add("/description", fmt::format("description is longer than {} characters", L::kMaxDescriptionLength));
  }

  check_provenance(doc, v);
  if (!doc.contains("bodies")) {
    v.add("/", "missing \"bodies\"");
  } else if (!doc["bodies"].is_array() || doc["bodies"].empty()) {
    v.add("/bodies", "bodies must be a non-empty array");
  } else if (doc["bodies"].size() > static_cast<std::size_t>(L::kMaxBodies)) {
    v.add("/bodies", fmt::format("more than {} bodies", L::kMaxBodies));
  } else {
    std::set<std::string> ids;
    for (std::size_t k = 0; k < doc["bodies"].size(); ++k) read_body(doc["bodies"][k], k, ids, v, out.bodies);
  }

  if (doc.contains("indenter")) {
    const json& i = doc["indenter"];
    if (i == "pad") {
      out.indenter = mat::Indenter::Pad;
    } else if (i == "finger") {
      out.indenter = mat::Indenter::Finger;
    } else {
      v.add("/indenter", "indenter must be \"pad\" or \"finger\", not " + brief(i));
    }
  }

  if (doc.contains("tumors")) {
    const json& t = doc["tumors"];
    if (!t.is_array()) {
      v.add("/tumors", std::string("tumors must be an array, not ") + t.type_name());
    } else {
      std::set<std::string> ids;
      for (const auto& b : out.bodies) ids.insert(b.id);
      const bool bodies_ok = v.ok();  // unknown-body errors only make sense when the bodies read cleanly
      for (std::size_t k = 0; k < t.size(); ++k) read_tumour(t[k], k, ids, bodies_ok, v, out.tumours);
    }
  }
  out.document = std::move(doc);
  return out;
}

}  // namespace

CaseError::CaseError(std::string file, std::vector<Problem> problems)
    : std::runtime_error(file + ": " + (problems.empty() ? std::string("invalid case")
                                                           : problems.front().where + ": " + problems.front().reason)),
      file_(std::move(file)),
      problems_(std::move(problems)) {}

std::vector<std::string> CaseError::lines() const {
  std::vector<std::string> out;
  for (const auto& p : problems_) out.push_back(file_ + ": " + p.where + ": " + p.reason);
  if (out.empty()) out.push_back(what());
  return out;
}

CaseFile parse_case(std::string_view text, const std::string& source) {
  json doc;
  if (auto problem = parse_json_text(text, L::kMaxDepth, L::kMaxValues, doc)) throw CaseError(source, {*problem});
  Validator v;
  CaseFile out = validate(std::move(doc), v);
  // "scoring" and "exam_region" (docs/scoring.md): every tool rejects a bad pass mark.
  std::vector<Problem> scoring;
  thresholds_from_case(out.document, scoring);
  training_from_case(out.document, scoring);  // "training" (io/training.hpp)
  for (auto& p : scoring) v.add(std::move(p.where), std::move(p.reason));
  if (!v.ok()) throw CaseError(source, v.take());
  return out;
}

CaseFile load_case(const std::filesystem::path& path) {
  std::string text;
  if (auto problem = read_text_file(path, L::kMaxFileBytes, text)) throw CaseError(path.string(), {*problem});
  return parse_case(text, path.string());
}

namespace {

// A body's material as it was authored: its modulus (the stiffness is derived from it) or
// its stiffness; the force model only where the file gave one or it is not the default.
void write_tissue(const mat::BodyGrid& g, json& b) {
  if (g.modulus.empty()) {
    b.erase("modulus");
    b.erase("poisson");
    b.erase("stiffening");
    b["stiffness"] = g.stiffness;
  } else {
    b.erase("stiffness");
    b["modulus"] = g.modulus;
    if (b.contains("poisson") || g.poisson != 0.49) b["poisson"] = g.poisson;
    if (g.stiffening > 0.0) b["stiffening"] = g.stiffening; else b.erase("stiffening");
  }
  const auto by_default = g.modulus.empty() ? mat::ForceModel::Paper : mat::ForceModel::Calibrated;
  if (b.contains("force_model") || g.force_model != by_default) b["force_model"] = mat::to_string(g.force_model);
}

}  // namespace

json to_json(const CaseFile& file) {
  json doc = file.document.is_object() ? file.document : json::object();
  doc["format"] = "palpa-case";
  doc["version"] = 1;
  doc["title"] = file.title;
  if (file.indenter == mat::Indenter::Finger || doc.contains("indenter")) doc["indenter"] = mat::to_string(file.indenter);
  const json old_bodies = doc.contains("bodies") && doc["bodies"].is_array() ? doc["bodies"] : json::array();
  json bodies = json::array();
  for (std::size_t k = 0; k < file.bodies.size(); ++k) {
    const auto& g = file.bodies[k];
    // Keep the unknown fields of the body this one was loaded from (matched by id).
    json b = json::object();
    for (const auto& old : old_bodies) {
      if (old.is_object() && old.contains("id") && old["id"] == g.id) b = old;
    }
    b["id"] = g.id;
    if (g.support == mat::Support::Bottom || b.contains("support")) b["support"] = mat::to_string(g.support);
    b["rows"] = g.rows;
    b["cols"] = g.cols;
    b["medial"] = g.medial;
    b["radius"] = g.radius;
    write_tissue(g, b);
    if (g.damping.empty()) b.erase("damping"); else b["damping"] = g.damping;
    if (g.mass.empty()) b.erase("mass"); else b["mass"] = g.mass;
    bodies.push_back(std::move(b));
  }
  doc["bodies"] = std::move(bodies);
  const json old_tumours = doc.contains("tumors") && doc["tumors"].is_array() ? doc["tumors"] : json::array();
  if (!file.tumours.empty() || doc.contains("tumors")) {
    json tumours = json::array();
    for (std::size_t k = 0; k < file.tumours.size(); ++k) {
      const auto& t = file.tumours[k];
      json o = k < old_tumours.size() && old_tumours[k].is_object() ? old_tumours[k] : json::object();
      o["body"] = t.body;
      o["center"] = t.center;
      o["radius"] = t.radius;
      if (t.modulus > 0.0) {
        o.erase("stiffness");
        o["modulus"] = t.modulus;
        if (t.stiffening > 0.0) o["stiffening"] = t.stiffening; else o.erase("stiffening");
      } else {
        o.erase("modulus");
        o.erase("stiffening");
        o["stiffness"] = t.stiffness;
      }
      tumours.push_back(std::move(o));
    }
    doc["tumors"] = std::move(tumours);
  }
  return doc;
}

void save_case(const CaseFile& file, const std::filesystem::path& path) {
  write_text_file_atomic(path, to_json(file).dump(2) + "\n");
}

}  // namespace palpa::io
