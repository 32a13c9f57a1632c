#pragma once
// What the instructor window draws: the case's bodies at rest (top and bottom contours,
// the top optionally coloured by the interpolated stiffness, with a legend) and its
// tumours as opaque spheres drawn in a layer over the bodies, so they show through the
// skin without translucency (a translucent actor costs ~9 ms a frame in llvmpipe).
#include <array>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <vtkSmartPointer.h>

#include "palpa/io/case_file.hpp"
#include "palpa/scene/scene.hpp"
#include "palpa/render/surface_pick.hpp"

class vtkActor;
class vtkLookupTable;
class vtkPolyData;
class vtkRenderer;
class vtkScalarBarActor;

namespace palpa::ui {

class InstructorScene {
 public:
  /// Adds its actors to `bodies` (layer 0) and `overlay` (a layer above, same camera).
  InstructorScene(vtkRenderer* bodies, vtkRenderer* overlay);
  ~InstructorScene();

  /// Fits and draws the bodies of `file` (its tumours are ignored here). Throws
  /// io::CaseError when a body cannot be fitted; the previous bodies stay drawn then.
  void set_bodies(const io::CaseFile& file);
  /// Draws these tumours (centre, radius); `selected` (an index) in another colour.
  void set_tumours(const std::vector<mat::Tumour>& tumours, std::optional<std::size_t> selected);
  /// Colours the top contours by stiffness (N/m), or by the tissue's modulus (kPa) when
  /// every body gives it, and shows the legend.
  void set_stiffness_overlay(bool on);
  bool stiffness_overlay() const { return overlay_on_; }

  bool has_bodies() const { return scene_ != nullptr; }
  /// The way out of the support the bodies rest on (ui::free_side); none for free bodies.
  std::optional<palpa::Vec3> free_side() const;
  /// The rest top contour under a ray (see render::TopContourPicker).
  std::optional<render::SurfacePick> pick(const palpa::Vec3& origin, const palpa::Vec3& direction) const;
  /// Bounds of the drawn body surfaces {xmin, xmax, ymin, ymax, zmin, zmax}.
  std::array<double, 6> bounds() const;
  std::size_t tumour_count() const { return tumours_.size(); }
  /// The range the overlay's colours span, in its unit (N/m, or kPa: overlay_in_kpa).
  std::array<double, 2> stiffness_range() const { return range_; }
  bool overlay_in_kpa() const { return in_kpa_; }
  /// What the legend reads: its tick labels, or on a uniform body its one value with the
  /// unit ("3.25 kPa").
  std::vector<std::string> legend_labels() const;
  /// A body's drawn top contour (tests read its points and scalars).
  vtkPolyData* top(std::size_t body) const;

 private:
  struct Surface {
    vtkSmartPointer<vtkPolyData> data;
    vtkSmartPointer<vtkActor> actor;
  };
  void clear_bodies();
  /// Sets the colours' and legend's range from range_ (one value on a uniform body).
  void show_legend_range();
  std::string legend_value(double value) const;

  vtkRenderer* bodies_;
  vtkRenderer* overlay_;
  std::unique_ptr<scene::Scene> scene_;
  std::unique_ptr<render::TopContourPicker> picker_;
  std::vector<Surface> surfaces_;  // top, bottom per body
  std::vector<vtkSmartPointer<vtkActor>> tumours_;
  vtkSmartPointer<vtkLookupTable> lut_;
  vtkSmartPointer<vtkScalarBarActor> legend_;
  std::array<double, 2> range_{0.0, 1.0};
  bool overlay_on_ = false;
  bool in_kpa_ = false;
  bool uniform_ = false;
};

}  // namespace palpa::ui
