#include "import_preview.hpp"

#include "mesh_polydata.hpp"

#include <algorithm>
#include <cmath>

#include <QHBoxLayout>
#include <QPlainTextEdit>
#include <vtkActor.h>
#include <vtkCellArray.h>
#include <vtkFloatArray.h>
#include <vtkGenericOpenGLRenderWindow.h>
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

#include "palpa/anatomy/height_field.hpp"
#include "palpa/render/tessellation.hpp"
#include "palpa/scene/scene.hpp"
#include "palpa/ui/body_view.hpp"
#include "palpa/ui/vtk_view.hpp"

namespace palpa::ui {
namespace {

constexpr double kTolerance = 2e-4;  // m, tessellation error, as the instructor's view

// mm from each vertex to the input free surface (NaN where the input has none).
std::vector<float> fit_errors(const anatomy::SurfacePair& surfaces, const render::Mesh& mesh) {
  std::vector<float> out(mesh.vertex_count());
  for (std::size_t v = 0; v < out.size(); ++v) {
    const Vec3 p(mesh.positions[3 * v], mesh.positions[3 * v + 1], mesh.positions[3 * v + 2]);
    out[v] = static_cast<float>(std::abs(anatomy::surface_distance(surfaces, surfaces.top, p)) * 1e3);
  }
  return out;
}

vtkSmartPointer<vtkActor> surface_actor(vtkPolyData* data, vtkLookupTable* lut) {
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputData(data);
  mapper->SetLookupTable(lut);
  mapper->SetScalarModeToUsePointData();
  mapper->UseLookupTableScalarRangeOn();
  mapper->ScalarVisibilityOn();
  auto actor = vtkSmartPointer<vtkActor>::New();
  actor->SetMapper(mapper);
  actor->GetProperty()->SetInterpolationToPhong();
  actor->GetProperty()->SetColor(0.70, 0.52, 0.46);
  return actor;
}

vtkSmartPointer<vtkScalarBarActor> make_legend(vtkLookupTable* lut) {
  auto legend = vtkSmartPointer<vtkScalarBarActor>::New();
  legend->SetLookupTable(lut);
  legend->SetTitle("fit error (mm)");
  legend->SetNumberOfLabels(5);
  legend->SetLabelFormat("%.2f");
  legend->SetMaximumWidthInPixels(110);
  legend->GetPositionCoordinate()->SetValue(0.86, 0.1);
  legend->SetWidth(0.12);
  legend->SetHeight(0.8);
  legend->UnconstrainedFontSizeOn();
  for (auto* text : {legend->GetTitleTextProperty(), legend->GetLabelTextProperty()}) {
    text->SetFontSize(13);
    text->ItalicOff();
    text->BoldOff();
    text->ShadowOff();
  }
  legend->VisibilityOff();
  return legend;
}

}  // namespace

ImportPreview::ImportPreview(QWidget* parent) : QWidget(parent) {
  auto* layout = new QHBoxLayout(this);
  layout->setContentsMargins(0, 0, 0, 0);
  view_ = new VtkView(this);
  view_->setMinimumSize(420, 320);
  summary_ = new QPlainTextEdit(this);
  summary_->setObjectName("importSummary");
  summary_->setReadOnly(true);
  summary_->setLineWrapMode(QPlainTextEdit::WidgetWidth);
  summary_->setMinimumWidth(380);
  layout->addWidget(view_, 3);
  layout->addWidget(summary_, 2);
  window_ = vtkSmartPointer<vtkGenericOpenGLRenderWindow>::New();
  window_->SetNumberOfLayers(2);
  renderer_ = add_body_renderer(*view_, window_);
  overlay_ = vtkSmartPointer<vtkRenderer>::New();  // lesions seen through the skin
  overlay_->SetLayer(1);
  overlay_->InteractiveOff();
  overlay_->SetActiveCamera(renderer_->GetActiveCamera());
  window_->AddRenderer(overlay_);
  lut_ = vtkSmartPointer<vtkLookupTable>::New();
  lut_->SetHueRange(0.33, 0.0);  // green (on the surface) to red (farthest)
  lut_->SetSaturationRange(0.85, 0.85);
  lut_->SetValueRange(0.95, 0.95);
  lut_->SetNanColor(0.6, 0.6, 0.6, 1.0);
  lut_->Build();
  legend_ = make_legend(lut_);
  renderer_->AddActor2D(legend_);
}

ImportPreview::~ImportPreview() = default;

void ImportPreview::clear() {
  if (top_actor_) renderer_->RemoveActor(top_actor_);
  top_actor_ = nullptr;
  top_ = nullptr;
  for (auto& a : lesions_) overlay_->RemoveActor(a);
  lesions_.clear();
  legend_->VisibilityOff();
  summary_->clear();
  if (isVisible()) window_->Render();
}

void ImportPreview::show_import(const anatomy_io::ImportedCase& imported) {
  clear();
  draw_top(imported);
  draw_lesions(imported);
  summary_->setPlainText(import_summary(imported));
  double b[6];
  top_->GetBounds(b);
  frame_from_front(*renderer_, {b[0], b[1], b[2], b[3], b[4], b[5]}, 0.75, 1.2);
  renderer_->ResetCameraClippingRange(b);
  if (isVisible()) window_->Render();
}

void ImportPreview::draw_top(const anatomy_io::ImportedCase& imported) {
  const auto scene = scene::Scene::build(imported.file, "import");  // throws io::CaseError
  const auto& body = scene.body(0).body;
  render::TessellationOptions options;
  options.tolerance = kTolerance;
  // The top contour only: where the tissue thins to nothing it lies on the bottom one,
  // and drawing both there would flicker between them.
  render::Mesh top;
  render::tessellate(body.top(), options, false, top);
  const std::vector<float> errors = fit_errors(imported.result.surfaces, top);
  float hi = 0.05f;  // mm: a perfect fit still gets a scale
  for (float e : errors) {
    if (std::isfinite(e)) hi = std::max(hi, e);
  }
  lut_->SetTableRange(0.0, hi);
  lut_->Build();
  top_ = mesh_polydata(top, &errors, "fit error (mm)");
  top_actor_ = surface_actor(top_, lut_);
  renderer_->AddActor(top_actor_);
  legend_->VisibilityOn();
}

void ImportPreview::draw_lesions(const anatomy_io::ImportedCase& imported) {
  for (const anatomy::Lesion& l : imported.result.lesions) {
    vtkNew<vtkSphereSource> sphere;
    sphere->SetRadius(std::max(l.radius, 1e-4));
    sphere->SetThetaResolution(24);
    sphere->SetPhiResolution(16);
    vtkNew<vtkPolyDataMapper> mapper;
    mapper->SetInputConnection(sphere->GetOutputPort());
    auto actor = vtkSmartPointer<vtkActor>::New();
    actor->SetMapper(mapper);
    actor->SetPosition(l.centre.x(), l.centre.y(), l.centre.z());
    if (l.kept) {
      actor->GetProperty()->SetColor(0.55, 0.20, 0.65);  // as the instructor's tumours
    } else {
      actor->GetProperty()->SetColor(0.75, 0.75, 0.80);
      actor->GetProperty()->SetOpacity(0.3);
    }
    overlay_->AddActor(actor);
    lesions_.push_back(actor);
  }
}

}  // namespace palpa::ui
