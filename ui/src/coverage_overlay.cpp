#include "palpa/ui/coverage_overlay.hpp"

#include <algorithm>

#include <Eigen/Geometry>

#include <vtkActor.h>
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
      cells_.emplace_back(b, k);
    }
  }
  vtkNew<vtkPolyData> dots;
  dots->SetPoints(points);
  dots->SetVerts(verts);
  dots->GetPointData()->SetScalars(colours_);
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputData(dots);
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

bool CoverageOverlay::sync() {
  if (coverage_.version() == drawn_version_) return false;
  drawn_version_ = coverage_.version();
  for (std::size_t d = 0; d < cells_.size(); ++d) {
    const auto level = std::min<std::uint8_t>(coverage_.levels(cells_[d].first)[cells_[d].second], 3);
    colours_->SetTypedTuple(static_cast<vtkIdType>(d), kColours[level].data());
  }
  colours_->Modified();
  return true;
}

void CoverageOverlay::set_visible(bool visible) { actor_->SetVisibility(visible); }

bool CoverageOverlay::visible() const { return actor_->GetVisibility() != 0; }

}  // namespace palpa::ui
