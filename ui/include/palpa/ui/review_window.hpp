#pragma once
// The review window: replays a recorded session over its case drawn at rest. The probe
// path (in-contact samples, thinned), the fingertip at the current time, the marks
// standing then, the tumours revealed; play/pause, speed, a scrubber, a readout of t, |F|
// and depth; plots of |F| and depth over the session with a cursor at t (SessionCharts,
// VTK charts; a click there seeks); the session's metrics (score::score_session) and
// Export report.
#include <QElapsedTimer>
#include <QMainWindow>
#include <QString>
#include <QTimer>
#include <filesystem>
#include <memory>
#include <vector>

#include <vtkSmartPointer.h>

#include "palpa/scene/scene.hpp"
#include "palpa/score/score.hpp"
#include "palpa/session/replay.hpp"
#include "palpa/live/display_meshes.hpp"
#include "palpa/ui/body_surfaces.hpp"

class QComboBox;
class QLabel;
class QListWidget;
class QPushButton;
class QSlider;
class QTableWidget;
class vtkActor;
class vtkGenericOpenGLRenderWindow;
class vtkRenderer;

namespace palpa::ui {

class SessionCharts;
class VtkView;

class ReviewWindow : public QMainWindow {
  Q_OBJECT
 public:
  /// `session` as read and `score` its score; `file` names the session file. Throws
  /// io::CaseError if the session's case document does not build a scene.
  ReviewWindow(session::Session session, score::Score score, std::filesystem::path file, QWidget* parent = nullptr);
  ~ReviewWindow() override;

  static constexpr double kFingertipRadius = 0.006;  ///< m: drawn probe
  static constexpr int kSliderSteps = 10000;         ///< scrubber resolution over the duration
  /// Paused, nothing moves: the view is redrawn at most this often (ms) unless a scrub, a
  /// seek or the mouse on the view changes it (VTK's interactor redraws those itself).
  static constexpr int kIdleRedrawMs = 250;

  const session::Session& session() const { return session_; }
  const score::Score& score() const { return score_; }
  session::TimeSpan span() const { return span_; }
  double time() const { return t_; }
  /// Index of the sample standing at the current time.
  std::size_t current_sample() const { return current_; }
  /// Centre of the drawn fingertip (m): the sample's probe point lifted one radius along +z.
  std::array<double, 3> fingertip_centre() const;
  bool playing() const { return playing_; }
  double speed() const { return speed_; }
  /// Marks standing at the current time (listed and drawn).
  std::size_t marks_shown() const;
  QSlider* scrubber() const { return scrubber_; }
  QPushButton* play_button() const { return play_button_; }
  QComboBox* speed_box() const { return speed_box_; }
  QTableWidget* metrics_table() const { return metrics_; }
  QLabel* readout() const { return readout_; }
  VtkView* view() const { return view_; }
  SessionCharts* charts() const { return charts_; }

  /// Writes STEM.html, .json, .xapi.json, .csv into `dir` (STEM: the session file's stem);
  /// false (with the reason in the status bar) on failure.
  bool export_report(const std::filesystem::path& dir);

 public slots:
  void set_time(double t);
  void play();
  void pause();
  void set_speed(double speed);
  /// One frame: advance time while playing, redraw.
  void frame();

 private:
  void build_scene();
  void build_path();
  void fill_metrics();
  void update_marks();
  void choose_export_folder();

  session::Session session_;
  score::Score score_;
  std::filesystem::path file_;
  session::TimeSpan span_;
  std::unique_ptr<scene::Scene> scene_;
  std::unique_ptr<live::DisplayMeshes> meshes_;
  std::unique_ptr<BodySurfaces> surfaces_;

  VtkView* view_ = nullptr;
  SessionCharts* charts_ = nullptr;
  QSlider* scrubber_ = nullptr;
  QPushButton* play_button_ = nullptr;
  QComboBox* speed_box_ = nullptr;
  QLabel* readout_ = nullptr;
  QListWidget* marks_list_ = nullptr;
  QTableWidget* metrics_ = nullptr;
  vtkSmartPointer<vtkGenericOpenGLRenderWindow> render_window_;
  vtkSmartPointer<vtkRenderer> renderer_;
  vtkSmartPointer<vtkActor> probe_;
  std::vector<vtkSmartPointer<vtkActor>> mark_actors_;  // marks and their lines to the tumours found
  std::size_t marks_drawn_for_ = static_cast<std::size_t>(-1);  // event count the mark actors show

  void render();

  QTimer timer_;
  QElapsedTimer play_clock_;
  QElapsedTimer since_render_;  // paused, the view is redrawn only now and then (kIdleRedrawMs)
  double t_ = 0.0;
  std::size_t current_ = 0;
  double speed_ = 1.0;
  bool playing_ = false;
};

}  // namespace palpa::ui
