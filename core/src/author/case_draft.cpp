#include "palpa/author/case_draft.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <fmt/format.h>

#include "palpa/io/json_text.hpp"
#include "palpa/mat/mat_body.hpp"
#include "palpa/scene/scene.hpp"
#include "palpa/render/surface_pick.hpp"

namespace palpa::author {
namespace {

using nlohmann::json;

std::array<double, 3> unit_normal(const std::array<double, 3>& n) {
  const double len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
  if (!(len > 0.0) || !std::isfinite(len)) throw std::invalid_argument("the surface normal has no direction");
  return {n[0] / len, n[1] / len, n[2] / len};
}

std::array<double, 3> below(const SurfacePoint& where, double depth) {
  const auto n = unit_normal(where.normal);
  return {where.point[0] - depth * n[0], where.point[1] - depth * n[1], where.point[2] - depth * n[2]};
}

std::optional<std::array<double, 3>> read_vec3(const json& v) {
  if (!v.is_array() || v.size() != 3) return std::nullopt;
  std::array<double, 3> out{};
  for (std::size_t c = 0; c < 3; ++c) {
    if (!v[c].is_number()) return std::nullopt;
    out[c] = v[c].get<double>();
  }
  return out;
}

std::optional<double> read_number(const json& obj, const char* key) {
  if (!obj.is_object() || !obj.contains(key) || !obj[key].is_number()) return std::nullopt;
  return obj[key].get<double>();
}

/// A tumour's material as the spec gives it: "modulus" (Pa) with its "stiffening" when it
/// has one, else "stiffness" (N/m); the other keys are removed.
void write_material(const TumourSpec& spec, json& t) {
  const bool by_modulus = spec.modulus > 0.0;
  t[by_modulus ? "modulus" : "stiffness"] = by_modulus ? spec.modulus : spec.stiffness;
  t.erase(by_modulus ? "stiffness" : "modulus");
  if (by_modulus && spec.stiffening > 0.0) t["stiffening"] = spec.stiffening; else t.erase("stiffening");
}

double distance(const std::array<double, 3>& a, const std::array<double, 3>& b) {
  return std::sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]));
}

}  // namespace

std::size_t approx_bytes(const json& value) {
  // An explicit stack: a document built by hand has no depth limit.
  constexpr std::size_t kNode = sizeof(json);
  constexpr std::size_t kMapEntry = 48;  // a std::map node's links and colour, besides its key and value
  std::size_t total = 0;
  std::vector<const json*> stack{&value};
  while (!stack.empty()) {
    const json* v = stack.back();
    stack.pop_back();
    total += kNode;
    if (v->is_string()) {
      total += sizeof(std::string) + v->get_ref<const std::string&>().capacity();
    } else if (v->is_array()) {
      total += sizeof(json::array_t);
      for (const auto& e : *v) stack.push_back(&e);
    } else if (v->is_object()) {
      total += sizeof(json::object_t);
      for (const auto& [key, e] : v->items()) {
        total += kMapEntry + sizeof(std::string) + key.capacity();
        stack.push_back(&e);
      }
    }
  }
  return total;
}

CaseDraft::CaseDraft(const PresetParams& params)
    : doc_(make_preset_case(params, std::string("New ") + to_string(params.preset) + " case").document) {}

CaseDraft CaseDraft::load(const std::filesystem::path& path) {
  std::string text;
  if (auto problem = io::read_text_file(path, io::CaseLimits::kMaxFileBytes, text)) {
    throw io::CaseError(path.string(), {*problem});
  }
  json doc;
  if (auto problem = io::parse_json_text(text, io::CaseLimits::kMaxDepth, io::CaseLimits::kMaxValues, doc)) {
    throw io::CaseError(path.string(), {*problem});
  }
  CaseDraft draft = from_document(std::move(doc), path.string());
  draft.path_ = path;
  return draft;
}

CaseDraft CaseDraft::from_document(json document, std::string source) {
  CaseDraft draft;
  draft.doc_ = std::move(document);
  draft.source_ = std::move(source);
  return draft;
}

std::string CaseDraft::source() const { return path_.empty() ? source_ : path_.string(); }

std::optional<io::CaseFile> CaseDraft::parsed() const {
  try {
    return io::parse_case(doc_.dump(), source());
  } catch (const io::CaseError&) {
    return std::nullopt;
  }
}

io::CaseFile CaseDraft::valid_case() const {
  // The text round trip applies the same limits as a file would meet.
  io::CaseFile file = io::parse_case(doc_.dump(), source());
  (void)scene::Scene::build(file, source());  // fits the bodies, tumours inside them
  bool rules = false;
  for (std::size_t k = 0; k < file.tumours.size(); ++k) rules = rules || scripted::placement_of(file, k).has_value();
  // A rule that can never be drawn would fail the first seeded exercise: try one seed now.
  if (rules) (void)scripted::place_tumours(file, 1, source());
  return file;
}

std::vector<io::Problem> CaseDraft::validate() const {
  try {
    (void)valid_case();
    return {};
  } catch (const io::CaseError& e) {
    return e.problems().empty() ? std::vector<io::Problem>{{"/", e.what()}} : e.problems();
  } catch (const std::exception& e) {
    return {{"/", std::string("cannot be checked: ") + e.what()}};
  }
}

void CaseDraft::save(const std::filesystem::path& path) {
  const io::CaseFile file = valid_case();
  io::save_case(file, path);
  path_ = path;
  saved_revision_ = revision_;
}

void CaseDraft::set_undo_limits(const UndoLimits& limits) {
  limits_ = limits;
  trim_history();
}

void CaseDraft::trim_history() {
  // The oldest first; one step always stays.
  std::size_t drop = 0;
  while (undo_.size() - drop > 1 && (undo_.size() - drop > limits_.steps || history_bytes_ > limits_.bytes)) {
    history_bytes_ -= undo_[drop].bytes;
    ++drop;
  }
  undo_.erase(undo_.begin(), undo_.begin() + static_cast<std::ptrdiff_t>(drop));
}

CaseDraft::State CaseDraft::take_current() {
  const std::size_t bytes = approx_bytes(doc_);
  return {std::move(doc_), revision_, bytes};
}

void CaseDraft::begin_edit() {
  for (const auto& s : redo_) history_bytes_ -= s.bytes;
  redo_.clear();
  State current{doc_, revision_, approx_bytes(doc_)};
  history_bytes_ += current.bytes;
  undo_.push_back(std::move(current));
  trim_history();
  revision_ = next_revision_++;
}

bool CaseDraft::undo() {
  if (undo_.empty()) return false;
  redo_.push_back(take_current());
  history_bytes_ += redo_.back().bytes;
  history_bytes_ -= undo_.back().bytes;
  doc_ = std::move(undo_.back().doc);
  revision_ = undo_.back().revision;
  undo_.pop_back();
  return true;
}

bool CaseDraft::redo() {
  if (redo_.empty()) return false;
  undo_.push_back(take_current());
  history_bytes_ += undo_.back().bytes;
  history_bytes_ -= redo_.back().bytes;
  doc_ = std::move(redo_.back().doc);
  revision_ = redo_.back().revision;
  redo_.pop_back();
  return true;
}

json CaseDraft::body_id(std::size_t b) const {
  const json& doc = doc_;  // const: operator[] must not insert
  if (!doc.is_object() || !doc.contains("bodies") || !doc["bodies"].is_array() || b >= doc["bodies"].size() ||
      !doc["bodies"][b].is_object() || !doc["bodies"][b].contains("id")) {
    throw std::out_of_range(fmt::format("no body {}", b));
  }
  return doc["bodies"][b]["id"];
}

json& CaseDraft::tumour_json(std::size_t k) {
  if (!doc_.is_object() || !doc_.contains("tumors") || !doc_["tumors"].is_array() || k >= doc_["tumors"].size() ||
      !doc_["tumors"][k].is_object()) {
    throw std::out_of_range(fmt::format("no tumour {}", k));
  }
  return doc_["tumors"][k];
}

void CaseDraft::swap_preset_scoring(const json& made) {
  // The old preset's scoring keys go unless the instructor changed them; the new preset's
  // come in (an instructor's own keys stay as they are).
  if (doc_.contains("preset") && doc_.contains("scoring") && doc_["scoring"].is_object()) {
    if (const auto old = preset_from_json(doc_["preset"])) {
      const json old_scoring = preset_scoring(old->preset);
      for (const auto& [key, value] : old_scoring.items()) {
        if (doc_["scoring"].contains(key) && doc_["scoring"][key] == value) doc_["scoring"].erase(key);
      }
      if (doc_["scoring"].empty()) doc_.erase("scoring");
    }
  }
  if (!made.contains("scoring")) return;
  if (!doc_.contains("scoring") || !doc_["scoring"].is_object()) doc_["scoring"] = json::object();
  for (const auto& [key, value] : made["scoring"].items()) doc_["scoring"][key] = value;
}

void CaseDraft::apply_preset(const PresetParams& params) {
  const io::CaseFile made = make_preset_case(params, title());  // throws before anything changes
  begin_edit();
  if (!doc_.is_object()) doc_ = json::object();
  swap_preset_scoring(made.document);
  doc_["bodies"] = made.document["bodies"];
  doc_["preset"] = made.document["preset"];
  const std::string id = made.bodies.front().id;
  if (doc_.contains("tumors") && doc_["tumors"].is_array()) {
    for (auto& t : doc_["tumors"]) {
      if (!t.is_object()) continue;
      t["body"] = id;
      // The tumour stays where it is; its anchor is a point of the old skin, so it goes:
      // the depth is then measured to the new skin straight above (anchor()).
      t.erase("anchor");
    }
  }
  // An exam region names the old bodies; the new body is examined whole.
  doc_.erase("exam_region");
}

void CaseDraft::set_title(const std::string& title) {
  // Checked first: a failed edit must not leave an undo step behind.
  if (!doc_.is_object() && !doc_.is_null()) throw std::invalid_argument("the case is not a JSON object: it has no title");
  begin_edit();
  doc_["title"] = title;
}

std::size_t CaseDraft::add_tumour(const SurfacePoint& where, const TumourSpec& spec) {
  const auto n = unit_normal(where.normal);
  const json id = body_id(where.body);
  begin_edit();
  if (!doc_.contains("tumors") || !doc_["tumors"].is_array()) doc_["tumors"] = json::array();
  json t = {{"body", id}, {"center", below(where, spec.depth)}, {"radius", spec.radius}};
  write_material(spec, t);
  t["anchor"] = {{"point", where.point}, {"normal", n}};
  doc_["tumors"].push_back(std::move(t));
  return doc_["tumors"].size() - 1;
}

void CaseDraft::move_tumour(std::size_t k, const SurfacePoint& where) {
  const auto old = spec(k);
  if (!old) throw std::out_of_range(fmt::format("tumour {} has no depth to keep", k));
  const auto n = unit_normal(where.normal);
  const json id = body_id(where.body);
  (void)tumour_json(k);
  begin_edit();
  json& t = tumour_json(k);
  t["body"] = id;
  t["center"] = below(where, old->depth);
  t["anchor"] = {{"point", where.point}, {"normal", n}};
}

void CaseDraft::edit_tumour(std::size_t k, const TumourSpec& spec) {
  (void)tumour_json(k);
  const auto old = this->spec(k);
  // Recomputing the centre from the anchor would round it: only a new depth moves it.
  const bool deeper = !old || old->depth != spec.depth;
  const auto where = deeper ? anchor(k) : std::nullopt;
  if (deeper && !where) throw std::out_of_range(fmt::format("tumour {} lies under no surface point", k));
  const auto n = deeper ? unit_normal(where->normal) : std::array<double, 3>{};
  begin_edit();
  json& t = tumour_json(k);
  if (deeper) {
    t["center"] = below(*where, spec.depth);
    t["anchor"] = {{"point", where->point}, {"normal", n}};
  }
  t["radius"] = spec.radius;
  write_material(spec, t);
}

void CaseDraft::remove_tumour(std::size_t k) {
  (void)tumour_json(k);
  begin_edit();
  doc_["tumors"].erase(k);
}

void CaseDraft::set_placement(std::size_t k, const std::optional<scripted::Placement>& rule) {
  (void)tumour_json(k);
  begin_edit();
  json& t = tumour_json(k);
  if (rule) {
    t["placement"] = {{"u", rule->u}, {"v", rule->v}, {"depth", rule->depth}};
  } else {
    t.erase("placement");
  }
}

void CaseDraft::apply_modulus_map(std::size_t b, const StiffnessMap& map, double e_min, double e_max) {
  const io::CaseFile file = io::parse_case(doc_.dump(), source());  // throws CaseError
  if (b >= file.bodies.size()) throw std::out_of_range(fmt::format("no body {}", b));
  mat::BodyGrid grid = file.bodies[b];
  if (grid.modulus.empty()) {
    throw std::invalid_argument(fmt::format("body {} gives its tissue in N/m, not as a modulus", b + 1));
  }
  try {
    author::apply_modulus_map(grid, map, e_min, e_max);
  } catch (const mat::FitError& e) {
    throw io::CaseError(source(), {{fmt::format("/bodies/{}/modulus", b), e.what()}});
  }
  begin_edit();
  doc_["bodies"][b]["modulus"] = grid.modulus;
}

void CaseDraft::apply_stiffness_map(std::size_t b, const StiffnessMap& map, double k_min, double k_max) {
  const io::CaseFile file = io::parse_case(doc_.dump(), source());  // throws CaseError
  if (b >= file.bodies.size()) throw std::out_of_range(fmt::format("no body {}", b));
  mat::BodyGrid grid = file.bodies[b];
  try {
    author::apply_stiffness_map(grid, map, k_min, k_max);
  } catch (const mat::FitError& e) {
    throw io::CaseError(source(), {{fmt::format("/bodies/{}/stiffness", b), e.what()}});
  }
  begin_edit();
  auto& body = doc_["bodies"][b];
  // A map is authored in N/m: a body given by its modulus becomes one given by stiffness,
  // keeping the force law it had (a modulus body's default is the calibrated one).
  if (!grid.modulus.empty()) {
    body.erase("modulus");
    body.erase("poisson");
    body.erase("stiffening");  // strain stiffening belongs to a modulus
    body["force_model"] = mat::to_string(grid.force_model);
  }
  body["stiffness"] = grid.stiffness;
}

std::string CaseDraft::title() const {
  return doc_.is_object() && doc_.contains("title") && doc_["title"].is_string() ? doc_["title"].get<std::string>()
                                                                                  : std::string();
}

std::optional<PresetParams> CaseDraft::preset() const {
  if (!doc_.is_object() || !doc_.contains("preset")) return std::nullopt;
  return preset_from_json(doc_["preset"]);
}

namespace {

// The mean of a body's per-point numbers under `key`, or 0 when it has none.
double mean_of(const json& body, const char* key) {
  if (!body.contains(key) || !body[key].is_array() || body[key].empty()) return 0.0;
  double sum = 0.0;
  for (const auto& x : body[key]) sum += x.is_number() ? x.get<double>() : 0.0;
  return sum / static_cast<double>(body[key].size());
}

}  // namespace

PresetParams CaseDraft::preset_or_nearest() const {
  if (auto made = preset()) return *made;
  PresetParams p = preset_defaults_in_kpa(Preset::Breast);
  if (!doc_.is_object() || !doc_.contains("bodies") || !doc_["bodies"].is_array() || doc_["bodies"].empty()) return p;
  const json& body = doc_["bodies"][0];
  if (!body.is_object()) return p;
  const auto limits = preset_limits(Preset::Breast);
  const auto within = [](double x, const double range[2]) { return std::clamp(x, range[0], range[1]); };
  if (body.contains("medial") && body["medial"].is_array() && !body["medial"].empty()) {
    constexpr double kInf = std::numeric_limits<double>::infinity();
    double lo[2] = {kInf, kInf}, hi[2] = {-kInf, -kInf};
    for (const auto& m : body["medial"]) {
      if (!m.is_array() || m.size() < 2 || !m[0].is_number() || !m[1].is_number()) continue;
      for (int k = 0; k < 2; ++k) {
        lo[k] = std::min(lo[k], m[static_cast<std::size_t>(k)].get<double>());
        hi[k] = std::max(hi[k], m[static_cast<std::size_t>(k)].get<double>());
      }
    }
    if (hi[0] > lo[0]) p.width = within(hi[0] - lo[0], limits.width);
    if (hi[1] > lo[1]) p.length = within(hi[1] - lo[1], limits.length);
  }
  if (body.contains("radius") && body["radius"].is_array()) {
    double largest = 0.0;
    for (const auto& r : body["radius"]) largest = std::max(largest, r.is_number() ? r.get<double>() : 0.0);
    if (largest > 0.0) p.thickness = within(2.0 * largest, limits.thickness);
  }
  if (const double e = mean_of(body, "modulus"); e > 0.0) {
    p.modulus = within(e, limits.modulus);
    p.stiffening = body.contains("stiffening") && body["stiffening"].is_number() ? body["stiffening"].get<double>() : 0.0;
  } else if (const double k = mean_of(body, "stiffness"); k > 0.0) {
    p.modulus = 0.0;
    p.stiffening = 0.0;
    p.stiffness = within(k, limits.stiffness);
  }
  return p;
}

bool CaseDraft::tissue_in_pa() const {
  if (!doc_.is_object() || !doc_.contains("bodies") || !doc_["bodies"].is_array() || doc_["bodies"].empty()) {
    return false;
  }
  return std::all_of(doc_["bodies"].begin(), doc_["bodies"].end(),
                     [](const json& b) { return b.is_object() && b.contains("modulus"); });
}

std::size_t CaseDraft::tumour_count() const {
  return doc_.is_object() && doc_.contains("tumors") && doc_["tumors"].is_array() ? doc_["tumors"].size() : 0;
}

std::optional<mat::Tumour> CaseDraft::tumour(std::size_t k) const {
  if (k >= tumour_count()) return std::nullopt;
  const json& t = doc_["tumors"][k];
  if (!t.is_object()) return std::nullopt;
  mat::Tumour out;
  if (t.contains("body") && t["body"].is_string()) out.body = t["body"].get<std::string>();
  const auto c = t.contains("center") ? read_vec3(t["center"]) : std::nullopt;
  const auto r = read_number(t, "radius"), s = read_number(t, "stiffness"), e = read_number(t, "modulus");
  if (!c || !r || (!s && !e)) return std::nullopt;
  out.center = *c;
  out.radius = *r;
  out.stiffness = s.value_or(0.0);
  out.modulus = s ? 0.0 : *e;
  out.stiffening = s ? 0.0 : read_number(t, "stiffening").value_or(0.0);
  return out;
}

std::optional<SurfacePoint> CaseDraft::anchor(std::size_t k) const {
  const auto t = tumour(k);
  if (!t) return std::nullopt;
  const json& obj = doc_["tumors"][k];
  std::size_t body = 0;
  if (doc_.contains("bodies") && doc_["bodies"].is_array()) {
    for (std::size_t b = 0; b < doc_["bodies"].size(); ++b) {
      const json& bj = doc_["bodies"][b];
      if (bj.is_object() && bj.contains("id") && bj["id"] == t->body) body = b;
    }
  }
  if (obj.contains("anchor") && obj["anchor"].is_object()) {
    const auto p = obj["anchor"].contains("point") ? read_vec3(obj["anchor"]["point"]) : std::nullopt;
    const auto n = obj["anchor"].contains("normal") ? read_vec3(obj["anchor"]["normal"]) : std::nullopt;
    if (p && n) return SurfacePoint{body, *p, *n};
  }
  // No recorded pick (a case written elsewhere): the top contour straight above the centre.
  const auto file = parsed();
  if (!file) return std::nullopt;
  io::CaseFile bodies_only = *file;
  bodies_only.tumours.clear();
  try {
    const auto scene = scene::Scene::build(bodies_only, source());
    const render::TopContourPicker picker(scene);
    const palpa::Vec3 centre(t->center[0], t->center[1], t->center[2]);
    const auto hit = picker.pick(centre, palpa::Vec3::UnitZ());
    if (!hit || hit->distance <= 0.0) return std::nullopt;
    // The normal from the centre to the hit, so that depth along it gives the centre back.
    const palpa::Vec3 n = (hit->point - centre).normalized();
    return SurfacePoint{hit->body, {hit->point.x(), hit->point.y(), hit->point.z()}, {n.x(), n.y(), n.z()}};
  } catch (const std::exception&) {
    return std::nullopt;
  }
}

std::optional<TumourSpec> CaseDraft::spec(std::size_t k) const {
  const auto t = tumour(k);
  const auto a = anchor(k);
  if (!t || !a) return std::nullopt;
  return TumourSpec{distance(a->point, t->center), t->radius, t->stiffness, t->modulus, t->stiffening};
}

std::optional<scripted::Placement> CaseDraft::placement(std::size_t k) const {
  if (k >= tumour_count()) return std::nullopt;
  const json& t = doc_["tumors"][k];
  if (!t.is_object() || !t.contains("placement")) return std::nullopt;
  const json& p = t["placement"];
  scripted::Placement out;
  for (auto [key, range] : {std::pair{"u", &out.u}, std::pair{"v", &out.v}, std::pair{"depth", &out.depth}}) {
    if (!p.is_object() || !p.contains(key) || !p[key].is_array() || p[key].size() != 2 || !p[key][0].is_number() ||
        !p[key][1].is_number()) {
      return std::nullopt;
    }
    *range = {p[key][0].get<double>(), p[key][1].get<double>()};
  }
  return out;
}

std::vector<std::optional<std::array<double, 2>>> CaseDraft::random_depth_ranges() const {
  std::vector<std::optional<std::array<double, 2>>> out(tumour_count());
  std::vector<std::size_t> ruled;
  for (std::size_t k = 0; k < out.size(); ++k) {
    if (placement(k) && tumour(k)) ruled.push_back(k);
  }
  if (ruled.empty()) return out;
  auto file = parsed();
  if (!file) return out;
  file->tumours.clear();
  std::optional<scene::Scene> scene;
  try {
    scene.emplace(scene::Scene::build(*file, source()));
  } catch (const std::exception&) {
    return out;
  }
  constexpr int kSamples = 9;
  for (const std::size_t k : ruled) {
    const auto rule = *placement(k);
    const std::string body = tumour(k)->body;
    for (std::size_t b = 0; b < scene->size(); ++b) {
      if (scene->body(b).body.id() != body) continue;
      double thin = std::numeric_limits<double>::infinity(), thick = 0.0;
      for (int i = 0; i < kSamples; ++i) {
        for (int j = 0; j < kSamples; ++j) {
          const double u = rule.u[0] + (rule.u[1] - rule.u[0]) * i / (kSamples - 1);
          const double v = rule.v[0] + (rule.v[1] - rule.v[0]) * j / (kSamples - 1);
          double s[mat::kRadius + 1];
          scene->body(b).body.skeleton().evaluate(u, v, s, mat::kRadius + 1);
          const double thickness = 2.0 * std::max(0.0, s[mat::kRadius]);  // as placement: 2R
          thin = std::min(thin, thickness);
          thick = std::max(thick, thickness);
        }
      }
      out[k] = std::array<double, 2>{rule.depth[0] * thin, rule.depth[1] * thick};
    }
  }
  return out;
}

void CaseDraft::set_description(const std::string& text) {
  if (!doc_.is_object() && !doc_.is_null()) throw std::invalid_argument("the case is not a JSON object: it has no description");
  begin_edit();
  if (text.empty()) {
    doc_.erase("description");
  } else {
    doc_["description"] = text;
  }
}

void CaseDraft::set_scoring(const std::string& key, std::optional<double> value) {
  if (!doc_.is_object() && !doc_.is_null()) throw std::invalid_argument("the case is not a JSON object: it has no scoring");
  begin_edit();
  if (value) {
    if (!doc_.contains("scoring") || !doc_["scoring"].is_object()) doc_["scoring"] = json::object();
    doc_["scoring"][key] = *value;
  } else if (doc_.contains("scoring") && doc_["scoring"].is_object()) {
    doc_["scoring"].erase(key);
    if (doc_["scoring"].empty()) doc_.erase("scoring");
  }
}

void CaseDraft::set_exam_region(const std::optional<ExamExtent>& extent) {
  if (!doc_.is_object() && !doc_.is_null()) throw std::invalid_argument("the case is not a JSON object: it has no exam region");
  std::vector<json> ids;
  if (extent) {
    for (std::size_t b = 0; doc_.contains("bodies") && doc_["bodies"].is_array() && b < doc_["bodies"].size(); ++b) {
      ids.push_back(body_id(b));  // throws before anything changes
    }
  }
  begin_edit();
  if (!extent) {
    doc_.erase("exam_region");
    return;
  }
  json region = json::array();
  for (const auto& id : ids) region.push_back({{"body", id}, {"u", extent->u}, {"v", extent->v}});
  doc_["exam_region"] = std::move(region);
}

std::string CaseDraft::description() const {
  return doc_.is_object() && doc_.contains("description") && doc_["description"].is_string()
             ? doc_["description"].get<std::string>()
             : std::string();
}

io::Thresholds CaseDraft::thresholds() const {
  std::vector<io::Problem> problems;
  return doc_.is_object() ? io::thresholds_from_case(doc_, problems) : io::Thresholds{};
}

CaseDraft::RegionKind CaseDraft::exam_region_kind() const {
  if (!doc_.is_object() || !doc_.contains("exam_region")) return RegionKind::Whole;
  return exam_extent() ? RegionKind::Extent : RegionKind::Custom;
}

std::optional<ExamExtent> CaseDraft::exam_extent() const {
  if (!doc_.is_object() || !doc_.contains("exam_region") || !doc_.contains("bodies")) return std::nullopt;
  const json& region = doc_["exam_region"];
  const json& bodies = doc_["bodies"];
  if (!region.is_array() || !bodies.is_array() || region.size() != bodies.size() || region.empty()) return std::nullopt;
  std::optional<ExamExtent> out;
  for (std::size_t b = 0; b < region.size(); ++b) {
    const json& part = region[b];
    if (!part.is_object() || !bodies[b].is_object() || !part.contains("body") || part["body"] != bodies[b]["id"]) {
      return std::nullopt;
    }
    ExamExtent e;
    for (auto [key, range] : {std::pair{"u", &e.u}, std::pair{"v", &e.v}}) {
      if (!part.contains(key)) continue;  // the whole range
      const json& r = part[key];
      if (!r.is_array() || r.size() != 2 || !r[0].is_number() || !r[1].is_number()) return std::nullopt;
      *range = {r[0].get<double>(), r[1].get<double>()};
    }
    if (out && !(*out == e)) return std::nullopt;
    out = e;
  }
  return out;
}

}  // namespace palpa::author
