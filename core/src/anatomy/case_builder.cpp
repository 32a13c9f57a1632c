// The case an import writes (docs/case-format.md, "Provenance"; docs/anatomy-import.md).
#include <algorithm>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "palpa/anatomy/import.hpp"
#include "palpa/anatomy/import_error.hpp"
#include "palpa/mat/mat_body.hpp"
#include "palpa/version.hpp"

namespace palpa::anatomy {

namespace {

using nlohmann::json;

// A world point in m, as everything in a case file.
json point_json(const Vec3& p) { return json::array({p.x(), p.y(), p.z()}); }

json fit_error(const ImportResult& r) {
  const FitReport& f = r.body.report;
  const auto one = [](const SurfaceError& e) {
    return json{{"max_m", e.max}, {"rms_m", e.rms}, {"interior_max_m", e.interior_max},
                {"interior_rms_m", e.interior_rms}, {"worst", point_json(e.worst)}};
  };
  return json{{"top", one(f.top)}, {"bottom", one(f.bottom)}, {"rim_band_m", f.rim_band}};
}

json lesions(const ImportResult& r) {
  json out = json::array();
  for (const Lesion& l : r.lesions) {
    json item{{"label", l.label}, {"name", l.name}, {"center", point_json(l.centre)}, {"radius", l.radius},
              {"voxels", l.voxels}, {"kept", l.kept}};
    if (!l.kept) item["skipped"] = l.skipped;
    out.push_back(std::move(item));
  }
  return out;
}

json provenance_json(const ImportResult& r, const Provenance& p) {
  json out{{"tool", "palpa-cli import"},
           {"palpa_version", kVersion},
           {"source", p.source},
           {"sha256", p.sha256},
           {"options", p.command},
           {"grid", fmt::format("{}x{}", r.body.grid.rows, r.body.grid.cols)},
           {"support_kind", r.surfaces.support_kind},
           {"resolution_m", r.surfaces.resolution},
           {"fit_error", fit_error(r)}};
  if (!p.labels.empty()) out["labels"] = p.labels;
  if (!p.support_source.empty()) out["support_source"] = p.support_source;
  if (!p.support_sha256.empty()) out["support_sha256"] = p.support_sha256;
  if (!r.lesions.empty()) out["lesions"] = lesions(r);
  return out;
}

// The exam region over the free surface: per interval of rows, the columns' span where the
// radius is above zero at either of its two rows, merged while the span stays the same.
json free_surface_region(const FittedBody& body) {
  mat::BodyGrid geometry = body.grid;
  geometry.stiffness.assign(geometry.point_count(), 1.0);
  geometry.modulus.clear();
  const mat::MatBody mat = mat::MatBody::fit(geometry);
  const auto& u = mat.u_params();
  const auto& v = mat.v_params();
  const int rows = body.grid.rows, cols = body.grid.cols;
  json parts = json::array();
  int lo_prev = -1, hi_prev = -1;
  for (int i = 0; i + 1 < rows; ++i) {
    int lo = cols, hi = -1;
    for (int j = 0; j < cols; ++j) {
      if (body.grid.radius[static_cast<std::size_t>(i * cols + j)] > 0.0 ||
          body.grid.radius[static_cast<std::size_t>((i + 1) * cols + j)] > 0.0) {
        lo = std::min(lo, j), hi = std::max(hi, j);
      }
    }
    if (hi < 0) continue;
    lo = std::max(lo - 1, 0), hi = std::min(hi + 1, cols - 1);
    if (lo == lo_prev && hi == hi_prev && !parts.empty()) {
      parts.back()["u"][1] = u[static_cast<std::size_t>(i + 1)];
      continue;
    }
    parts.push_back({{"body", body.grid.id},
                     {"u", {u[static_cast<std::size_t>(i)], u[static_cast<std::size_t>(i + 1)]}},
                     {"v", {v[static_cast<std::size_t>(lo)], v[static_cast<std::size_t>(hi)]}}});
    lo_prev = lo, hi_prev = hi;
  }
  return parts;
}

}  // namespace

io::CaseFile make_case(const ImportResult& result, const Provenance& provenance, const std::string& title,
                       ExamRegion region) {
  io::CaseFile file;
  file.title = title;
  file.bodies.push_back(result.body.grid);
  file.tumours = result.tumours;
  json doc = io::to_json(file);
  doc["provenance"] = provenance_json(result, provenance);
  if (region == ExamRegion::FreeSurface) doc["exam_region"] = free_surface_region(result.body);
  try {
    return io::parse_case(doc.dump(), provenance.source);
  } catch (const io::CaseError& e) {
    throw ImportError(fmt::format("the imported case is not valid: {}", e.lines().front()));
  }
}

}  // namespace palpa::anatomy
