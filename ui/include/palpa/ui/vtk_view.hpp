#pragma once
// The VTK view every Palpa window uses: VTK draws into its own native OpenGL window
// (QVTKOpenGLStereoWidget, a QOpenGLWindow in a widget container) instead of
// QVTKOpenGLNativeWidget's QOpenGLWidget. The native widget makes Qt compose the whole
// top-level window through OpenGL on every frame (its texture plus every raster widget),
// which under Mesa llvmpipe costs as much as VTK's own render: in the same window with
// one lit sphere, 73 fps with the native widget against 143 fps here (BENCHMARKS.md,
// "Graphics frame rate").
//
// The view's mouse, wheel and key events arrive at the embedded window, input(): install
// event filters there, and send synthetic events there in tests.
#include <utility>

#include <Eigen/Core>
#include <QImage>
#include <QPoint>
#include <QVTKOpenGLStereoWidget.h>

class QWindow;
class vtkRenderer;

namespace palpa::ui {

class VtkView : public QVTKOpenGLStereoWidget {
  Q_OBJECT
 public:
  explicit VtkView(QWidget* parent = nullptr);

  /// Receives the view's mouse, wheel and key events.
  QWindow* input() const;
  /// The view's last frame as drawn (for screenshots); null before the first frame.
  QImage frame();

  /// The line under a view pixel (widget coordinates) as seen through `renderer`: its
  /// points on the near and far clipping planes (m, scene coordinates).
  std::pair<Eigen::Vector3d, Eigen::Vector3d> pointer_ray(vtkRenderer& renderer, const QPoint& pos) const;
  /// Where a scene point (m) appears in the view (widget pixels).
  QPoint to_view(vtkRenderer& renderer, const Eigen::Vector3d& point) const;
};

}  // namespace palpa::ui
