#pragma once
// The anatomy import's preview in the instructor's Import anatomy dialog: the fitted body's
// top contour coloured by its distance to the input free surface (mm, with a legend), the
// lesions found as spheres (kept solid, skipped faint), and a summary in mm and kPa.
#include <vector>

#include <QString>
#include <QWidget>

#include <vtkActor.h>
#include <vtkGenericOpenGLRenderWindow.h>
#include <vtkLookupTable.h>
#include <vtkPolyData.h>
#include <vtkRenderer.h>
#include <vtkScalarBarActor.h>
#include <vtkSmartPointer.h>

#include "palpa/anatomy_io/import_request.hpp"

class QPlainTextEdit;

namespace palpa::ui {

class VtkView;

/// What the import found, for people: grid, fit error top and bottom, tissue, tumours and
/// skipped lesions, in mm and kPa (as palpa-cli import prints it).
QString import_summary(const anatomy_io::ImportedCase& imported);

class ImportPreview : public QWidget {
  Q_OBJECT
 public:
  explicit ImportPreview(QWidget* parent = nullptr);
  ~ImportPreview() override;

  /// Draws and describes an import; throws io::CaseError when its body cannot be built.
  void show_import(const anatomy_io::ImportedCase& imported);
  /// Back to nothing shown.
  void clear();
  /// The drawn top contour, with its "fit error (mm)" point scalars (null before an import).
  vtkPolyData* top() const { return top_; }
  vtkScalarBarActor* legend() const { return legend_; }
  int lesion_actors() const { return static_cast<int>(lesions_.size()); }

 private:
  void draw_top(const anatomy_io::ImportedCase& imported);
  void draw_lesions(const anatomy_io::ImportedCase& imported);

  VtkView* view_ = nullptr;
  QPlainTextEdit* summary_ = nullptr;
  vtkSmartPointer<vtkGenericOpenGLRenderWindow> window_;
  vtkSmartPointer<vtkRenderer> renderer_, overlay_;
  vtkSmartPointer<vtkLookupTable> lut_;
  vtkSmartPointer<vtkScalarBarActor> legend_;
  vtkSmartPointer<vtkPolyData> top_;
  vtkSmartPointer<vtkActor> top_actor_;
  std::vector<vtkSmartPointer<vtkActor>> lesions_;
};

}  // namespace palpa::ui
