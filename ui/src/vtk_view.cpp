#include "palpa/ui/vtk_view.hpp"

#include <cmath>

#include <QVTKOpenGLWindow.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>

namespace palpa::ui {

VtkView::VtkView(QWidget* parent) : QVTKOpenGLStereoWidget(parent) {
  // Keyboard focus reaches the embedded window through the container.
  setFocusPolicy(Qt::StrongFocus);
}

QWindow* VtkView::input() const { return embeddedOpenGLWindow(); }

QImage VtkView::frame() {
  // grabFramebuffer() draws a frame into the window's framebuffer and reads it back.
  if (!isVisible() || !embeddedOpenGLWindow()->isExposed()) return {};
  return embeddedOpenGLWindow()->grabFramebuffer();
}

std::pair<Eigen::Vector3d, Eigen::Vector3d> VtkView::pointer_ray(vtkRenderer& renderer, const QPoint& pos) const {
  // VTK's display coordinates are device pixels with y up.
  const double dpr = devicePixelRatioF();
  const int* size = renderer.GetRenderWindow()->GetSize();
  const double x = pos.x() * dpr;
  const double y = size[1] - 1 - pos.y() * dpr;
  Eigen::Vector3d ends[2];
  for (int k = 0; k < 2; ++k) {  // display depth 0: near plane, 1: far plane
    renderer.SetDisplayPoint(x, y, k);
    renderer.DisplayToWorld();
    double w[4];
    renderer.GetWorldPoint(w);
    ends[k] = Eigen::Vector3d(w[0], w[1], w[2]) / (w[3] != 0.0 ? w[3] : 1.0);
  }
  return {ends[0], ends[1]};
}

QPoint VtkView::to_view(vtkRenderer& renderer, const Eigen::Vector3d& point) const {
  renderer.SetWorldPoint(point.x(), point.y(), point.z(), 1.0);
  renderer.WorldToDisplay();
  double d[3];
  renderer.GetDisplayPoint(d);
  const double dpr = devicePixelRatioF();
  const int* size = renderer.GetRenderWindow()->GetSize();
  return {static_cast<int>(std::lround(d[0] / dpr)), static_cast<int>(std::lround((size[1] - 1 - d[1]) / dpr))};
}

}  // namespace palpa::ui
