#include "palpa/ui/coverage_overlay.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/Geometry>

#include <vtkActor.h>
#include <vtkCamera.h>
#include <vtkCellArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkProperty.h>
#include <vtkRenderer.h>
#include <vtkUnsignedCharArray.h>

namespace palpa::ui {
namespace {

constexpr double kLift = 0.0008;  // m: the dots float this far off the rest skin (no z-fighting)
constexpr float kDotPixels = 3.0F;

}  // namespace

std::vector<Vec3> cell_normals(const live::LiveCoverage& coverage, std::size_t body, const Vec3& outward) {
  const int rows = coverage.rows(body), cols = coverage.cols(body);
  const auto& c = coverage.centers(body);
  const auto& area = coverage.areas(body);
  const auto at = [&](int i, int j) { return c[static_cast<std::size_t>(i * cols + j)]; };
  std::vector<Vec3> n(c.size(), Vec3::UnitZ());
  Vec3 mean = Vec3::Zero();
  for (int i = 0; i < rows; ++i) {
    for (int j = 0; j < cols; ++j) {
      const Vec3 du = at(std::min(i + 1, rows - 1), j) - at(std::max(i - 1, 0), j);
      const Vec3 dv = at(i, std::min(j + 1, cols - 1)) - at(i, std::max(j - 1, 0));
      const Vec3 cross = du.cross(dv);
      const auto k = static_cast<std::size_t>(i * cols + j);
      if (cross.norm() > 0.0) n[k] = cross.normalized();
      mean += area[k] * n[k];
    }
  }
  if (mean.dot(outward) < 0.0)
    for (auto& v : n) v = -v;
  return n;
}

RegionFacing region_facing(const live::LiveCoverage& coverage, const Vec3& bodies_centre) {
  RegionFacing out;
  Vec3 moment = Vec3::Zero();
  for (std::size_t b = 0; b < coverage.bodies(); ++b) {
    const auto& area = coverage.areas(b);
    const auto& c = coverage.centers(b);
    for (std::size_t k = 0; k < c.size(); ++k) {
      if (!(area[k] > 0.0)) continue;
      moment += area[k] * c[k];
      out.area += area[k];
      out.points.push_back(c[k]);
    }
  }
  if (!(out.area > 0.0)) return out;
  out.centroid = moment / out.area;
  Vec3 mean = Vec3::Zero();
  for (std::size_t b = 0; b < coverage.bodies(); ++b) {
    const auto n = cell_normals(coverage, b, out.centroid - bodies_centre);
    const auto& area = coverage.areas(b);
    for (std::size_t k = 0; k < n.size(); ++k) mean += area[k] * n[k];
  }
  if (mean.norm() > 0.0) out.normal = mean.normalized();
  return out;
}

CoverageOverlay::CoverageOverlay(const live::LiveCoverage& coverage, vtkRenderer* renderer, const Vec3& eye)
    : coverage_(coverage), renderer_(renderer) {
  vtkNew<vtkPoints> points;
  vtkNew<vtkCellArray> verts;
  colours_ = vtkSmartPointer<vtkUnsignedCharArray>::New();
  colours_->SetNumberOfComponents(3);
  colours_->SetName("level");
  for (std::size_t b = 0; b < coverage.bodies(); ++b) {
    const auto& c = coverage.centers(b);
    const auto& area = coverage.areas(b);
    Vec3 centroid = Vec3::Zero();
    for (const auto& p : c) centroid += p;
    if (!c.empty()) centroid /= static_cast<double>(c.size());
    const auto normals = cell_normals(coverage, b, eye - centroid);
    for (std::size_t k = 0; k < c.size(); ++k) {
      if (!(area[k] > 0.0)) continue;
      const Vec3 p = c[k] + kLift * normals[k];
      verts->InsertNextCell(1);
      verts->InsertCellPoint(points->InsertNextPoint(p.x(), p.y(), p.z()));
      colours_->InsertNextTypedTuple(kColours[0].data());
      shown_.push_back(cells_.size());
      cells_.emplace_back(b, k);
    }
  }
  dots_ = vtkSmartPointer<vtkPolyData>::New();
  dots_->SetPoints(points);
  dots_->SetVerts(verts);
  dots_->GetPointData()->SetScalars(colours_);
  stride_.assign(coverage.bodies(), 1);
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputData(dots_);
  mapper->SetColorModeToDirectScalars();
  actor_ = vtkSmartPointer<vtkActor>::New();
  actor_->SetMapper(mapper);
  actor_->GetProperty()->SetPointSize(kDotPixels);
  actor_->GetProperty()->LightingOff();
  actor_->PickableOff();
  renderer_->AddActor(actor_);
  sync();
}

CoverageOverlay::~CoverageOverlay() { renderer_->RemoveActor(actor_); }

std::uint8_t CoverageOverlay::block_level(std::size_t body, std::size_t cell) const {
  const int s = stride_[body], cols = coverage_.cols(body), rows = coverage_.rows(body);
  const auto& levels = coverage_.levels(body);
  const auto& area = coverage_.areas(body);
  const int i0 = static_cast<int>(cell) / cols, j0 = static_cast<int>(cell) % cols;
  std::uint8_t least = 3;
  for (int i = i0; i < std::min(rows, i0 + s); ++i)
    for (int j = j0; j < std::min(cols, j0 + s); ++j) {
      const auto k = static_cast<std::size_t>(i * cols + j);
      if (area[k] > 0.0) least = std::min(least, levels[k]);
    }
  return least;
}

bool CoverageOverlay::sync() {
  if (coverage_.version() == drawn_version_) return false;
  drawn_version_ = coverage_.version();
  // Only the dots drawn: each stands for its s x s block, so this visits every cell once
  // (colouring every dot by its block cost s^2 per cell: ~20 ms a frame with 35 bodies far off).
  for (const std::size_t d : shown_) {
    const auto [body, cell] = cells_[d];
    const auto level = stride_[body] > 1 ? block_level(body, cell) : std::min<std::uint8_t>(coverage_.levels(body)[cell], 3);
    colours_->SetTypedTuple(static_cast<vtkIdType>(d), kColours[level].data());
  }
  colours_->Modified();
  return true;
}

namespace {
// px on screen between two scene points (m).
double pixels_between(vtkRenderer& r, const Vec3& a, const Vec3& b) {
  double da[3], db[3];
  r.SetWorldPoint(a.x(), a.y(), a.z(), 1.0);
  r.WorldToDisplay();
  r.GetDisplayPoint(da);
  r.SetWorldPoint(b.x(), b.y(), b.z(), 1.0);
  r.WorldToDisplay();
  r.GetDisplayPoint(db);
  return std::hypot(da[0] - db[0], da[1] - db[1]);
}
}  // namespace

bool CoverageOverlay::fit_to_view() {
  auto* camera = renderer_->GetActiveCamera();
  if (!camera || renderer_->GetSize()[0] <= 0) return false;
  // Where the camera is and looks, and the view's size: not its modification time, which
  // every render's clipping-range reset bumps.
  std::array<double, 12> view{};
  camera->GetPosition(view.data());
  camera->GetFocalPoint(view.data() + 3);
  camera->GetViewUp(view.data() + 6);
  view[9] = camera->GetViewAngle() + camera->GetParallelScale();
  view[10] = renderer_->GetSize()[0];
  view[11] = renderer_->GetSize()[1];
  if (view == camera_view_) return false;
  camera_view_ = view;
  auto strides = stride_;
  for (std::size_t b = 0; b < coverage_.bodies(); ++b) {
    const int rows = coverage_.rows(b), cols = coverage_.cols(b);
    if (rows < 2 || cols < 2) continue;
    const auto& c = coverage_.centers(b);
    const auto at = [&](int i, int j) { return c[static_cast<std::size_t>(i * cols + j)]; };
    // The grid's spacing on screen: the median over a 5 x 5 sample of its cells of the closer
    // of their two directions (slopes seen at a slant lie closer).
    std::vector<double> spacings;
    for (int a = 1; a <= 5; ++a)
      for (int e = 1; e <= 5; ++e) {
        const int i = std::max(1, a * rows / 6), j = std::max(1, e * cols / 6);
        spacings.push_back(std::min(pixels_between(*renderer_, at(i - 1, j), at(i, j)), pixels_between(*renderer_, at(i, j - 1), at(i, j))));
      }
    std::nth_element(spacings.begin(), spacings.begin() + 12, spacings.end());
    const double spacing = spacings[12];
    strides[b] = spacing > 0.0 ? std::clamp(static_cast<int>(std::ceil(kMinSpacing / spacing)), 1, 16) : 1;
  }
  if (strides == stride_) return false;
  stride_ = strides;
  vtkNew<vtkCellArray> verts;
  shown_.clear();
  for (std::size_t d = 0; d < cells_.size(); ++d) {
    const auto [body, cell] = cells_[d];
    const int cols = coverage_.cols(body), s = stride_[body];
    if ((static_cast<int>(cell) / cols) % s != 0 || (static_cast<int>(cell) % cols) % s != 0) continue;
    shown_.push_back(d);
    verts->InsertNextCell(1);
    verts->InsertCellPoint(static_cast<vtkIdType>(d));
  }
  dots_->SetVerts(verts);
  drawn_version_ = ~std::uint64_t{0};  // the blocks' colours anew
  sync();
  return true;
}

std::vector<Vec3> CoverageOverlay::shown_dots() const {
  std::vector<Vec3> out;
  auto* verts = dots_->GetVerts();
  vtkIdType n = 0;
  const vtkIdType* ids = nullptr;
  verts->InitTraversal();
  while (verts->GetNextCell(n, ids)) {
    double p[3];
    dots_->GetPoint(ids[0], p);
    out.emplace_back(p[0], p[1], p[2]);
  }
  return out;
}

void CoverageOverlay::set_visible(bool visible) { actor_->SetVisibility(visible); }

bool CoverageOverlay::visible() const { return actor_->GetVisibility() != 0; }

}  // namespace palpa::ui
