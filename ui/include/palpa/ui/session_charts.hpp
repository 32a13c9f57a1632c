#pragma once
// The review window's plots, drawn with VTK's charts (vtkContextView, vtkChartXY) in a
// VtkView of their own: the indentation depth (mm, left axis) and |F| (N, right axis) over
// the whole session, the depth line coloured by the pressure level reached (light, medium,
// deep: the case's thresholds over the local tissue thickness), the safety limit when the
// force comes near it, a vertical marker at each Mark event and a cursor at the replay time.
//
// The series are built once; set_cursor() moves only the cursor's two points, so a replay
// frame never rebuilds the chart, and redraws only when the cursor changes pixel column.
// Each series is decimated to at most kMaxPoints by keeping the smallest and the largest
// sample of each bucket (and the first and last), so peaks survive. A left click in the
// plot area asks to seek there (seek_requested).
#include <QWidget>
#include <vtkSmartPointer.h>

#include "palpa/scene/scene.hpp"
#include "palpa/score/score.hpp"
#include "palpa/session/replay.hpp"
#include "palpa/session/session.hpp"

class QLabel;
class vtkChartXY;
class vtkContextView;
class vtkGenericOpenGLRenderWindow;
class vtkTable;

namespace palpa::ui {

class VtkView;

class SessionCharts : public QWidget {
  Q_OBJECT
 public:
  static constexpr std::size_t kMaxPoints = 4000;  ///< per series

  /// `scene` (the session's case) gives the tissue thickness for the pressure levels; with
  /// none the depth line is drawn in one colour. The time axis covers `span`, labelled in
  /// s from its start.
  SessionCharts(const session::Session& session, const score::Score& score, const scene::Scene* scene,
                session::TimeSpan span, QWidget* parent = nullptr);
  ~SessionCharts() override;

  /// Moves the cursor to session time t (s, on the samples' clock) and redraws.
  void set_cursor(double t);
  /// Session time (s) of the cursor.
  double cursor_time() const { return cursor_t_; }
  /// The cursor's column in the chart (device pixels from the left; -1 before the first
  /// frame), and the column of the last frame drawn: the chart redraws only when it changes.
  int cursor_pixel() const;
  int drawn_cursor_pixel() const { return drawn_pixel_; }
  /// Session time (s) under a point of the view (widget pixels, y down); clamped to the
  /// time axis.
  double time_at(QPoint pixel) const;

  VtkView* view() const { return view_; }
  vtkChartXY* chart() const;
  /// Columns "t (s)" (s from start) and "|F| (N)".
  vtkTable* force_table() const;
  /// Columns "t (s)", "depth (mm)" and "level" (0 no contact, 1 light, 2 medium, 3 deep).
  vtkTable* depth_table() const;
  /// Two rows (bottom, top) per mark marker, drawn as separate segments.
  vtkTable* mark_table() const;
  /// Two rows: the cursor's bottom and top.
  vtkTable* cursor_table() const;
  std::size_t mark_markers() const;

 signals:
  /// A left click in the chart: seek the replay to session time t (s).
  void seek_requested(double t);

 private:
  void build(const session::Session& session, const score::Score& score, const scene::Scene* scene);
  void add_plots(bool show_limit, double duration, double deepest_mm);

  void on_press();

  session::TimeSpan span_;
  double cursor_t_ = 0.0;
  double force_top_ = 1.0;  // N: the force axis' top, the markers' height
  int drawn_pixel_ = -1;
  VtkView* view_ = nullptr;
  QLabel* legend_ = nullptr;
  vtkSmartPointer<vtkGenericOpenGLRenderWindow> render_window_;
  vtkSmartPointer<vtkContextView> context_;
  vtkSmartPointer<vtkChartXY> chart_;
  vtkSmartPointer<vtkTable> force_, depth_, marks_, cursor_, limit_;
  vtkSmartPointer<vtkTable> level_segments_[4];  // the depth line's segments by pressure level
  unsigned long press_observer_ = 0;
};

}  // namespace palpa::ui
