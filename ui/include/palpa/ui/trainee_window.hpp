#pragma once
// The trainee exercise window: the 3D view of the case (bodies deforming under the probe,
// drawn as a fingertip), the force gauge, the marks, Finish and the score card, and a
// status bar with the haptic loop's health. Everything it shows comes from
// live::LiveExercise; everything the trainee does goes to it.
//
// Mouse: the pointer picks a point on the body and the finger follows the skin there at
// the chosen pressure; the wheel (or Up/Down) steps the pressure through light, medium and
// deep (three steps each), or in force mode the target force. Left drag turns the view,
// Ctrl+wheel zooms. M marks the finger's position. Keys work while the window is active.
#include <QElapsedTimer>
#include <QMainWindow>
#include <QPoint>
#include <QTimer>
#include <memory>
#include <optional>
#include <vector>

#include <vtkSmartPointer.h>

#include "palpa/io/training.hpp"
#include "palpa/live/live_coverage.hpp"
#include "palpa/live/live_exercise.hpp"
#include "palpa/live/stroke_trace.hpp"
#include "palpa/render/level_of_detail.hpp"
#include "palpa/ui/body_surfaces.hpp"

class QCheckBox;
class QKeyEvent;
class QVBoxLayout;
class QLabel;
class QListWidget;
class QPushButton;
class vtkActor;
class vtkGenericOpenGLRenderWindow;
class vtkRenderer;
class vtkRegularPolygonSource;

namespace palpa::ui {

class VtkView;

class ForceGauge;
class PushBackTrace;
class ScoreCard;
class CoverageOverlay;

class TraineeWindow : public QMainWindow {
  Q_OBJECT
 public:
  /// A dynamic property: set it true on the window before closing it to close without the
  /// question (a signal, the application quitting); the attempt then ends complete.
  static constexpr const char* kCloseWithoutAsking = "palpaCloseWithoutAsking";
  /// A dynamic property (a string): with kCloseWithoutAsking, a running attempt is abandoned
  /// with this reason ("SIGTERM", "window destroyed": the End note "abandoned: SIGTERM")
  /// instead of ending complete.
  static constexpr const char* kCloseReason = "palpaCloseReason";
  /// Takes the exercise; starts it (session recording, haptic loop) unless `start` is false
  /// (a screenshot needs no session). Throws what LiveExercise::start throws.
  TraineeWindow(std::unique_ptr<live::LiveExercise> exercise, const QString& case_name, bool start = true,
                QWidget* parent = nullptr);
  ~TraineeWindow() override;

  live::LiveExercise& exercise() { return *exercise_; }
  VtkView* view() const { return view_; }
  ForceGauge* gauge() const { return gauge_; }
  /// The push-back trace under the gauge (objectName "pushBackTrace").
  PushBackTrace* push_back_trace() const { return trace_; }
  /// The finger sticks on firm tissue (the pseudo-haptic control/display ratio,
  /// docs/perception.md): checkbox "stickyFinger", on by default.
  bool sticky_finger() const;
  /// px between the pointer and the finger shown (0 unless the finger sticks).
  double finger_lag() const { return control_display_.lag(); }
  /// The message shown when the chosen device faulted and the mouse took over (hidden before).
  QLabel* device_banner() const { return device_banner_; }
  BodySurfaces& surfaces() { return *surfaces_; }
  vtkRenderer* renderer() const { return renderer_; }
  /// Where a scene point (m) appears in the view (widget pixels).
  QPoint to_view(const palpa::Vec3& point) const;
  /// The pressure chosen with the wheel or the keys (level mode).
  const live::PressureDial& pressure() const { return dial_; }
  /// Force mode: the finger sinks until |F| reaches this (N); 0 in level mode.
  double force_target() const { return force_target_; }
  /// The line under the gauge that names the chosen pressure, e.g. "Pressure: medium, step 2 of 3".
  QString pressure_text() const;
  /// The score card, once finished.
  ScoreCard* score_card() const { return score_card_; }
  const std::optional<score::Score>& score() const { return score_; }
  /// Frames drawn per second over the last second.
  double frame_rate() const { return frame_rate_; }
  /// The live coverage of the exam region (live_coverage.hpp): coverage() and
  /// deep_coverage() as the score measures them, fed from every snapshot.
  const live::LiveCoverage& live_coverage() const { return *coverage_; }
  /// The figure in the side panel (objectName "liveCoverage"), e.g. "Covered so far: 45.3%
  /// (deep 12.0%)", rounded like the score card (score/figures.hpp).
  QString coverage_text() const;
  /// The coverage overlay is drawn on the body now (checkbox "coverageOverlay", key C;
  /// never when the case's "training" turns it off).
  bool coverage_overlay_shown() const;
  /// The case's "training" options (the overlay allowed or not).
  const io::TrainingOptions& training() const { return training_; }
  /// The share (0..1, area-weighted) of the exam region that the pointer can reach from the
  /// current view: each cell centre of the score's grid projected to the view and picked
  /// back through the window's own picking lands within 1 mm of itself.
  double exam_region_view_share() const;
  /// The last second drew nothing that changed (the status bar says "idle").
  bool idle() const { return idle_; }

  /// Where the last frame() spent its time (s), for palpa --bench: taking the snapshot and
  /// re-tessellating changed bodies, copying them into VTK, and VTK's render.
  struct FrameTimes {
    double tessellate = 0.0;
    double upload = 0.0;
    double render = 0.0;
    std::size_t bodies_changed = 0;
    std::size_t bodies_drawn = 0;  ///< in the camera's view (the rest are culled)
    std::size_t triangles = 0;     ///< drawn: the visible bodies' tops and bottoms
  };
  const FrameTimes& last_frame() const { return last_frame_; }
  /// Points the camera at one body, close enough that its middle fills the view (palpa
  /// --bench measures the culling of the others this way).
  void look_at_body(std::size_t body);
  /// Level of detail: each body's drawn contours within this many pixels of its surface
  /// by the tessellation's bound, at the body's largest magnification (default
  /// kDetailPixels), and never coarser than the exercise's tolerance in metres allows
  /// close up; 0 draws every body at that tolerance however small it is on screen.
  void set_detail_pixels(double pixels);
  static constexpr double kDetailPixels = 0.5;
  /// The largest distance between a drawn triangle and the surface it stands for, over the
  /// visible bodies, in pixels at each body's largest magnification (DisplayMeshes::
  /// deviation: samples every triangle, for tests and palpa --bench, not every frame).
  double drawn_deviation_px() const;
  /// Milliseconds between timed frames (16 by default, ~60 Hz); 0 draws whenever the event
  /// loop is idle; a negative value stops the timer (a driver then calls frame() itself).
  void set_frame_interval(int ms);

 signals:
  /// The session file is finished and closed (scored or not: `scored` says): it may be
  /// uploaded now. Emitted once per exercise, also when the window closes.
  void session_ended(const QString& session_path, bool scored);

 public slots:
  /// The state of the finished session's upload, in words, in the status bar (objectName
  /// "uploadState"); empty hides it.
  void show_upload_state(const QString& text);
  /// The pointer is at `pos` (view pixels): pick the body there and press at the depth set.
  void palpate_at(const QPoint& pos);
  /// Steps the pressure (level mode: one of nine settings; force mode: 1 N).
  void step_pressure(int steps);
  /// Force mode on with a target in [1, 15] N, or off (level mode) with 0.
  void set_force_mode(double newtons);
  void place_mark();
  void remove_selected_mark();
  void finish();
  /// One frame: take the newest snapshot, copy changed bodies, move the probe, redraw.
  void frame();

 protected:
  bool eventFilter(QObject* watched, QEvent* event) override;
  void keyPressEvent(QKeyEvent* event) override;
  void closeEvent(QCloseEvent* event) override;

 private:
  QWidget* build_side_panel(QWidget* central, QPushButton*& mark_button);
  void build_status_bar();
  void add_coverage_controls(QVBoxLayout* side, QWidget* central);
  void feed_coverage(const engine::SceneSnapshot& snapshot);
  void build_scene();
  void update_status();
  void reveal(const score::Score& score);
  enum class CloseChoice { FinishAndScore, Abandon, GoOn, Finish };
  /// The question on closing a running exercise (objectName "closeQuestion").
  CloseChoice ask_before_closing();
  /// M, Up/Down, F; Ctrl+W closes the window, Ctrl+Q all windows.
  bool handle_key(const QKeyEvent& event);
  /// After the score: a mark that found a tumour green, a duplicate amber, a false one red.
  void colour_mark(const score::MarkResult& mark);
  void apply_pressure();
  /// The window's pick under a view pixel (the bodies' top contours), if any.
  std::optional<render::SurfacePick> pick_at(const QPoint& pos) const;
  /// Each frame: the push-back trace reads what the finger slid over since the last one,
  /// and a finger left behind by the control/display ratio catches up with a resting pointer.
  void feel();
  void show_contact_ring(const live::FeltPoint& at);
  /// The pressure setting as the trace compares it (the dial's step, or the force target).
  double pressure_setting() const { return force_target_ > 0.0 ? 100.0 + force_target_ : dial_.index(); }
  /// Off-screen culling: marks each body visible or not from the camera's frustum (its rest
  /// box grown by a margin for deformation), and gives each visible one the grid its size
  /// on screen is worth (level of detail); fills the frame's bodies_drawn and triangles.
  void fit_bodies_to_view();
  /// The camera as the level of detail needs it.
  render::ViewForDetail detail_view() const;
  /// The largest magnification of body b's rest box from `view` (render::pixels_per_metre).
  double pixels_per_metre(const render::ViewForDetail& view, std::size_t body) const;
  /// Body b's display tolerance (m) for detail_pixels_ on screen; 0 when the level of detail is off.
  double detail_tolerance(const render::ViewForDetail& view, std::size_t body) const;
  void request_render() { render_requested_ = true; }

  std::unique_ptr<live::LiveExercise> exercise_;
  VtkView* view_ = nullptr;
  ForceGauge* gauge_ = nullptr;
  QLabel* device_banner_ = nullptr;  ///< shown once the chosen device faulted (unplugged)
  QListWidget* marks_list_ = nullptr;
  QPushButton* remove_button_ = nullptr;
  QPushButton* finish_button_ = nullptr;
  QPushButton* mark_button_ = nullptr;
  QLabel* status_loop_ = nullptr;
  QLabel* status_fps_ = nullptr;
  QLabel* status_upload_ = nullptr;
  ScoreCard* score_card_ = nullptr;
  vtkSmartPointer<vtkGenericOpenGLRenderWindow> render_window_;
  vtkSmartPointer<vtkRenderer> renderer_;
  std::unique_ptr<BodySurfaces> surfaces_;
  std::unique_ptr<live::LiveCoverage> coverage_;
  std::unique_ptr<CoverageOverlay> overlay_;
  io::TrainingOptions training_;
  QLabel* coverage_label_ = nullptr;
  QCheckBox* overlay_box_ = nullptr;
  std::uint64_t fed_tick_ = 0;
  std::uint64_t shown_coverage_version_ = 0;
  vtkSmartPointer<vtkActor> probe_;
  vtkSmartPointer<vtkActor> ring_;  // the contact ring (show_contact_ring)
  vtkSmartPointer<vtkRegularPolygonSource> ring_source_;
  palpa::Vec3 drawn_ring_ = palpa::Vec3::Zero();
  std::vector<std::pair<std::int64_t, vtkSmartPointer<vtkActor>>> mark_actors_;
  QTimer timer_;
  QElapsedTimer fps_clock_;
  int frames_ = 0;
  int changed_frames_ = 0;  ///< frames drawn in this second because something changed
  bool idle_ = false;       ///< the last second drew only the idle redraws
  double frame_rate_ = 0.0;
  FrameTimes last_frame_;
  double detail_pixels_ = kDetailPixels;
  /// The next frame() draws (something changed); otherwise an unchanged scene is redrawn
  /// only every kIdleRedrawMs while the timer drives the frames.
  bool render_requested_ = true;
  bool skip_unchanged_ = true;
  QElapsedTimer since_render_;
  palpa::Vec3 drawn_probe_ = palpa::Vec3::Zero();
  static constexpr int kIdleRedrawMs = 250;
  static constexpr double kProbeMoveToDraw = 1e-5;  ///< m: a tenth of a pixel at the closest zoom
  live::PressureDial dial_;
  double force_target_ = 0.0;  // N; 0: level mode
  int wheel_rest_ = 0;         // wheel angle not yet a whole notch
  QLabel* pressure_label_ = nullptr;
  PushBackTrace* trace_ = nullptr;
  QCheckBox* sticky_box_ = nullptr;
  live::ControlDisplay control_display_;
  std::optional<QPoint> pointer_;  // where the pointer last was over the view (px)
  QElapsedTimer pointer_clock_;    // since control_display_ last followed it
  QCheckBox* force_mode_ = nullptr;
  std::optional<render::SurfacePick> picked_;
  std::optional<score::Score> score_;
  std::string scheduling_;
};

}  // namespace palpa::ui
