#include "palpa/ui/instructor_scene.hpp"

#include "mesh_polydata.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <vtkActor.h>
#include <vtkCellArray.h>
#include <vtkFloatArray.h>
#include <vtkLookupTable.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkProperty.h>
#include <vtkRenderer.h>
#include <vtkScalarBarActor.h>
#include <vtkSphereSource.h>
#include <vtkTextProperty.h>
#include <vtkVariant.h>

#include <fmt/format.h>

#include "palpa/mat/mat_body.hpp"
#include "palpa/render/tessellation.hpp"
#include "palpa/ui/body_view.hpp"

namespace palpa::ui {
namespace {

constexpr double kTolerance = 2e-4;  // m, tessellation error

// The skeleton's stiffness at each vertex of a contour mesh: vertex (i, j) lies over
// SK(us[i], vs[j]) (a contour and its skeleton share their parameters).
std::vector<float> vertex_stiffness(const mat::MatBody& body, const render::Mesh& mesh) {
  std::vector<float> out(mesh.vertex_count());
  double sample[mat::kSkeletonChannels];
  for (int i = 0; i < mesh.rows; ++i) {
    for (int j = 0; j < mesh.cols; ++j) {
      body.skeleton().evaluate(mesh.us[static_cast<std::size_t>(i)], mesh.vs[static_cast<std::size_t>(j)], sample);
      out[static_cast<std::size_t>(i) * static_cast<std::size_t>(mesh.cols) + static_cast<std::size_t>(j)] =
          static_cast<float>(std::max(0.0, sample[mat::kStiffness]));
    }
  }
  return out;
}

// The interval of sorted sites holding t and t's share of the way across it.
std::pair<std::size_t, double> locate(const std::vector<double>& sites, double t) {
  const auto hi = std::upper_bound(sites.begin() + 1, sites.end() - 1, t);
  const auto k = static_cast<std::size_t>(hi - sites.begin()) - 1;
  const double w = sites[k + 1] > sites[k] ? (t - sites[k]) / (sites[k + 1] - sites[k]) : 0.0;
  return {k, std::clamp(w, 0.0, 1.0)};
}

// The tissue's modulus (kPa) at each vertex of a contour mesh: the authored modulus of the
// grid points bilinear between their parameters, exact at the points and never outside
// their range (the stiffness the case derives from it also follows the thickness).
std::vector<float> vertex_modulus(const mat::MatBody& body, const mat::BodyGrid& grid, const render::Mesh& mesh) {
  std::vector<float> out(mesh.vertex_count());
  const auto& su = body.u_params();
  const auto& sv = body.v_params();
  const auto at = [&](std::size_t i, std::size_t j) { return grid.modulus[i * static_cast<std::size_t>(grid.cols) + j]; };
  for (std::size_t i = 0; i < mesh.us.size(); ++i) {
    const auto [a, wu] = locate(su, mesh.us[i]);
    for (std::size_t j = 0; j < mesh.vs.size(); ++j) {
      const auto [b, wv] = locate(sv, mesh.vs[j]);
      const double e = (1 - wu) * ((1 - wv) * at(a, b) + wv * at(a, b + 1)) +
                       wu * ((1 - wv) * at(a + 1, b) + wv * at(a + 1, b + 1));
      out[i * mesh.vs.size() + j] = static_cast<float>(1e-3 * e);
    }
  }
  return out;
}

}  // namespace

InstructorScene::InstructorScene(vtkRenderer* bodies, vtkRenderer* overlay) : bodies_(bodies), overlay_(overlay) {
  lut_ = vtkSmartPointer<vtkLookupTable>::New();
  lut_->SetHueRange(0.66, 0.0);  // blue (soft) to red (stiff)
  lut_->SetSaturationRange(0.85, 0.85);
  lut_->SetValueRange(0.95, 0.95);
  lut_->Build();
  legend_ = vtkSmartPointer<vtkScalarBarActor>::New();
  legend_->SetLookupTable(lut_);
  legend_->SetTitle("Stiffness (N/m)");
  legend_->SetNumberOfLabels(5);
  legend_->SetLabelFormat("%.0f");
  legend_->SetMaximumWidthInPixels(110);
  legend_->GetPositionCoordinate()->SetValue(0.88, 0.1);
  legend_->SetWidth(0.1);
  legend_->SetHeight(0.8);
  legend_->UnconstrainedFontSizeOn();
  for (auto* text : {legend_->GetTitleTextProperty(), legend_->GetLabelTextProperty()}) {
    text->SetFontSize(13);
    text->ItalicOff();
    text->BoldOff();
    text->ShadowOff();
  }
  legend_->VisibilityOff();
  bodies_->AddActor2D(legend_);
}

InstructorScene::~InstructorScene() = default;

void InstructorScene::clear_bodies() {
  for (auto& s : surfaces_) bodies_->RemoveActor(s.actor);
  surfaces_.clear();
}

void InstructorScene::set_bodies(const io::CaseFile& file) {
  io::CaseFile bodies_only = file;
  bodies_only.tumours.clear();
  auto scene = std::make_unique<scene::Scene>(scene::Scene::build(bodies_only, "case"));  // throws CaseError
  auto picker = std::make_unique<render::TopContourPicker>(*scene);
  clear_bodies();
  range_ = {std::numeric_limits<double>::max(), 0.0};
  // The overlay speaks kPa when every body gives its tissue by its modulus.
  in_kpa_ = !file.bodies.empty() && std::all_of(file.bodies.begin(), file.bodies.end(),
                                                 [](const mat::BodyGrid& g) { return !g.modulus.empty(); });
  legend_->SetTitle(in_kpa_ ? "Modulus (kPa)" : "Stiffness (N/m)");
  legend_->SetLabelFormat(in_kpa_ ? "%.1f" : "%.0f");
  render::TessellationOptions options;
  options.tolerance = kTolerance;
  for (std::size_t b = 0; b < scene->size(); ++b) {
    const auto& body = scene->body(b).body;
    for (int side = 0; side < 2; ++side) {
      render::Mesh mesh;
      render::tessellate(side == 0 ? body.top() : body.bottom(), options, side == 1, mesh);
      std::vector<float> k;
      if (side == 0) {
        k = in_kpa_ ? vertex_modulus(body, file.bodies[b], mesh) : vertex_stiffness(body, mesh);
        for (float x : k) range_ = {std::min<double>(range_[0], x), std::max<double>(range_[1], x)};
      }
      Surface s;
      s.data = mesh_polydata(mesh, side == 0 ? &k : nullptr, "Stiffness");
      vtkNew<vtkPolyDataMapper> mapper;
      mapper->SetInputData(s.data);
      mapper->SetLookupTable(lut_);
      mapper->SetScalarModeToUsePointData();
      mapper->UseLookupTableScalarRangeOn();
      mapper->SetScalarVisibility(side == 0 && overlay_on_);
      s.actor = vtkSmartPointer<vtkActor>::New();
      s.actor->SetMapper(mapper);
      auto* property = s.actor->GetProperty();
      property->SetInterpolationToPhong();
      if (side == 0) {
        property->SetColor(0.93, 0.74, 0.64);  // skin, as the trainee window
      } else {
        property->SetColor(0.70, 0.52, 0.46);
      }
      // As the trainee window: no back faces. Where the contours meet (the flat rim of a
      // breast on its chest wall, seen head-on from its free side) the bottom's back faces
      // would show through the top in a checkerboard.
      property->BackfaceCullingOn();
      property->SetSpecular(0.25);
      property->SetSpecularPower(20.0);
      bodies_->AddActor(s.actor);
      surfaces_.push_back(std::move(s));
    }
  }
  if (range_[0] > range_[1]) range_ = {0.0, 1.0};
  show_legend_range();
  scene_ = std::move(scene);
  picker_ = std::move(picker);
}

void InstructorScene::show_legend_range() {
  // A uniform body (within float round-off) is one value: the legend says exactly that,
  // not a made-up range of one unit above it.
  const double lo = range_[0], hi = range_[1];
  uniform_ = hi - lo <= 1e-4 * std::max(1.0, std::abs(hi));
  lut_->ResetAnnotations();
  if (uniform_) {
    const double value = 0.5 * (lo + hi);
    range_ = {value, value};
    lut_->SetTableRange(value, value + std::max(1e-9, 1e-6 * std::abs(value)));  // one colour
    lut_->SetAnnotation(vtkVariant(value), legend_value(value).c_str());
  } else {
    lut_->SetTableRange(lo, hi);
  }
  legend_->SetDrawTickLabels(!uniform_);
  lut_->Build();
}

std::string InstructorScene::legend_value(double value) const {
  return fmt::format("{:.4g} {}", value, in_kpa_ ? "kPa" : "N/m");
}

std::vector<std::string> InstructorScene::legend_labels() const {
  std::vector<std::string> out;
  if (uniform_) {
    out.push_back(lut_->GetAnnotation(0).c_str());
    return out;
  }
  const double* r = lut_->GetRange();
  const int n = legend_->GetNumberOfLabels();
  for (int k = 0; k < n; ++k) {
    const double x = n > 1 ? r[0] + (r[1] - r[0]) * k / (n - 1) : r[0];
    out.push_back(in_kpa_ ? fmt::format("{:.1f}", x) : fmt::format("{:.0f}", x));  // as the label format
  }
  return out;
}

void InstructorScene::set_tumours(const std::vector<mat::Tumour>& tumours, std::optional<std::size_t> selected) {
  for (auto& a : tumours_) overlay_->RemoveActor(a);
  tumours_.clear();
  for (std::size_t k = 0; k < tumours.size(); ++k) {
    const auto& t = tumours[k];
    vtkNew<vtkSphereSource> sphere;
    sphere->SetRadius(std::max(t.radius, 1e-4));
    sphere->SetThetaResolution(24);
    sphere->SetPhiResolution(16);
    vtkNew<vtkPolyDataMapper> mapper;
    mapper->SetInputConnection(sphere->GetOutputPort());
    auto actor = vtkSmartPointer<vtkActor>::New();
    actor->SetMapper(mapper);
    actor->SetPosition(t.center[0], t.center[1], t.center[2]);
    if (selected && *selected == k) {
      actor->GetProperty()->SetColor(1.0, 0.55, 0.05);  // the tumour being edited
    } else {
      actor->GetProperty()->SetColor(0.55, 0.20, 0.65);
    }
    overlay_->AddActor(actor);
    tumours_.push_back(actor);
  }
}

void InstructorScene::set_stiffness_overlay(bool on) {
  overlay_on_ = on;
  for (std::size_t k = 0; k < surfaces_.size(); k += 2) surfaces_[k].actor->GetMapper()->SetScalarVisibility(on);
  legend_->SetVisibility(on && !surfaces_.empty());
}

std::optional<render::SurfacePick> InstructorScene::pick(const palpa::Vec3& origin,
                                                          const palpa::Vec3& direction) const {
  if (!picker_) return std::nullopt;
  return picker_->pick(origin, direction);
}

std::optional<palpa::Vec3> InstructorScene::free_side() const {
  if (!scene_) return std::nullopt;
  return ui::free_side(*scene_);
}

std::array<double, 6> InstructorScene::bounds() const {
  std::array<double, 6> out{std::numeric_limits<double>::max(), -std::numeric_limits<double>::max(),
                            std::numeric_limits<double>::max(), -std::numeric_limits<double>::max(),
                            std::numeric_limits<double>::max(), -std::numeric_limits<double>::max()};
  for (const auto& s : surfaces_) {
    double b[6];
    s.data->GetBounds(b);
    for (std::size_t k = 0; k < 3; ++k) {
      out[2 * k] = std::min(out[2 * k], b[2 * k]);
      out[2 * k + 1] = std::max(out[2 * k + 1], b[2 * k + 1]);
    }
  }
  return out;
}

vtkPolyData* InstructorScene::top(std::size_t body) const {
  return 2 * body < surfaces_.size() ? surfaces_[2 * body].data.Get() : nullptr;
}

}  // namespace palpa::ui
