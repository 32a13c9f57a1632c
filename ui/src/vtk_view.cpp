#include "palpa/ui/vtk_view.hpp"

#include <QVTKOpenGLWindow.h>

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

}  // namespace palpa::ui
