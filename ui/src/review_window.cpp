#include "palpa/ui/review_window.hpp"

#include "palpa/score/figures.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <system_error>

#include <QComboBox>
#include <QFileDialog>
#include <QMessageBox>
#include <QGroupBox>
#include <QHBoxLayout>
#include <QHeaderView>
#include <QLabel>
#include <QListWidget>
#include <QPushButton>
#include <QSlider>
#include <QStatusBar>
#include <QTableWidget>
#include <QVBoxLayout>
#include <vtkActor.h>
#include <vtkCamera.h>
#include <vtkCellArray.h>
#include <vtkGenericOpenGLRenderWindow.h>
#include <vtkInteractorStyleTrackballCamera.h>
#include <vtkLineSource.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkProperty.h>
#include <vtkRenderWindowInteractor.h>
#include <vtkRenderer.h>
#include <vtkSphereSource.h>

#include "palpa/io/case_file.hpp"
#include "palpa/report/session_header.hpp"
#include "palpa/report/session_report.hpp"
#include "palpa/ui/session_charts.hpp"
#include "palpa/ui/body_view.hpp"
#include "palpa/ui/vtk_view.hpp"
#include "palpa/ui/window_frame.hpp"

namespace palpa::ui {
namespace {

constexpr double kPathStep = 0.001;  // m between kept path points
constexpr double kMarkRadius = 0.0025;  // m

vtkSmartPointer<vtkActor> sphere(const std::array<double, 3>& centre, double radius, double r, double g, double b) {
  vtkNew<vtkSphereSource> source;
  source->SetRadius(radius);
  source->SetThetaResolution(24);
  source->SetPhiResolution(16);
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputConnection(source->GetOutputPort());
  auto actor = vtkSmartPointer<vtkActor>::New();
  actor->SetMapper(mapper);
  actor->SetPosition(centre[0], centre[1], centre[2]);
  actor->GetProperty()->SetColor(r, g, b);
  actor->GetProperty()->SetInterpolationToPhong();
  return actor;
}

double norm(const std::array<double, 3>& v) { return std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]); }


}  // namespace

ReviewWindow::ReviewWindow(session::Session session, score::Score score, std::filesystem::path file, QWidget* parent)
    : QMainWindow(parent), session_(std::move(session)), score_(std::move(score)), file_(std::move(file)) {
  span_ = session::time_span(session_);
  t_ = span_.start;
  const auto placed = io::parse_case(session_.info.case_document.dump(), file_.string());
  scene_ = std::make_unique<scene::Scene>(scene::Scene::build(placed, file_.string()));
  meshes_ = std::make_unique<live::DisplayMeshes>(*scene_);

  setWindowTitle(tr("Palpa: review (%1, trainee %2)")
                     .arg(QString::fromStdString(file_.filename().string()), QString::fromStdString(session_.info.trainee)));
  fit_to_screen(*this, {1200, 696});  // a 1280 x 800 screen under a title bar and a panel

  auto* central = new QWidget(this);
  auto* layout = new QHBoxLayout(central);
  auto* left = new QVBoxLayout;
  view_ = new VtkView(central);
  left->addWidget(view_, 1);
  charts_ = new SessionCharts(session_, score_, scene_.get(), span_, central);
  charts_->setFixedHeight(230);
  left->addWidget(charts_);
  auto* controls = new QHBoxLayout;
  play_button_ = new QPushButton(tr("Play"), central);
  speed_box_ = new QComboBox(central);
  for (double s : {0.25, 0.5, 1.0, 2.0, 4.0, 8.0}) speed_box_->addItem(QString::number(s) + "x", s);
  speed_box_->setCurrentIndex(2);
  scrubber_ = new QSlider(Qt::Horizontal, central);
  scrubber_->setRange(0, kSliderSteps);
  controls->addWidget(play_button_);
  controls->addWidget(speed_box_);
  controls->addWidget(scrubber_, 1);
  left->addLayout(controls);
  readout_ = new QLabel(central);
  left->addWidget(readout_);
  layout->addLayout(left, 1);

  auto* side = new QVBoxLayout;
  auto* metrics_box = new QGroupBox(tr("Metrics"), central);
  auto* metrics_layout = new QVBoxLayout(metrics_box);
  metrics_ = new QTableWidget(metrics_box);
  metrics_layout->addWidget(metrics_);
  side->addWidget(metrics_box, 3);
  auto* marks_box = new QGroupBox(tr("Marks standing"), central);
  auto* marks_layout = new QVBoxLayout(marks_box);
  marks_list_ = new QListWidget(marks_box);
  marks_layout->addWidget(marks_list_);
  side->addWidget(marks_box, 1);
  auto* export_button = new QPushButton(tr("Export report..."), central);
  side->addWidget(export_button);
  auto* side_widget = new QWidget(central);
  side_widget->setLayout(side);
  side_widget->setFixedWidth(340);
  layout->addWidget(side_widget);
  setCentralWidget(central);
  statusBar()->showMessage(tr("%1 samples, %2 s; device %3%4")
                               .arg(static_cast<qulonglong>(session_.samples.size()))
                               .arg(span_.end - span_.start, 0, 'f', 1)
                               .arg(QString::fromStdString(session_.info.device))
                               .arg(session_.complete ? QString() : tr(" (incomplete session)")));

  connect(play_button_, &QPushButton::clicked, this, [this] { playing_ ? pause() : play(); });
  connect(speed_box_, qOverload<int>(&QComboBox::currentIndexChanged), this,
          [this](int index) { set_speed(speed_box_->itemData(index).toDouble()); });
  connect(scrubber_, &QSlider::valueChanged, this, [this](int value) {
    set_time(span_.start + (span_.end - span_.start) * value / static_cast<double>(kSliderSteps));
  });
  connect(charts_, &SessionCharts::seek_requested, this, &ReviewWindow::set_time);
  connect(export_button, &QPushButton::clicked, this, &ReviewWindow::choose_export_folder);
  connect(&timer_, &QTimer::timeout, this, &ReviewWindow::frame);

  build_scene();
  fill_metrics();
  set_time(span_.start);
  timer_.start(16);
  close_on_ctrl_w(*this, view_->input());  // as the trainee and instructor windows
}

ReviewWindow::~ReviewWindow() = default;

void ReviewWindow::build_scene() {
  render_window_ = vtkSmartPointer<vtkGenericOpenGLRenderWindow>::New();
  renderer_ = add_body_renderer(*view_, render_window_);

  surfaces_ = std::make_unique<BodySurfaces>(*meshes_, renderer_);
  surfaces_->set_opacity(0.35);  // the tumours are revealed inside
  // A body on a support from its free side (an imported breast faces +y), others from the front.
  if (const auto up = free_side(*scene_)) {
    frame_from_free_side(*renderer_, scene_bounds(*scene_), *up);
  } else {
    frame_from_front(*renderer_, scene_bounds(*scene_));
  }

  for (const auto& t : score_.tumours) {
    renderer_->AddActor(t.found ? sphere(t.center, t.radius, 0.20, 0.65, 0.25) : sphere(t.center, t.radius, 0.75, 0.15, 0.15));
  }
  build_path();
  probe_ = sphere({0.0, 0.0, 0.0}, kFingertipRadius, 0.85, 0.88, 0.95);
  probe_->GetProperty()->SetOpacity(0.9);
  renderer_->AddActor(probe_);
}

void ReviewWindow::build_path() {
  vtkNew<vtkPoints> points;
  vtkNew<vtkCellArray> lines;
  for (const auto& stretch : session::contact_path(session_.samples, kPathStep)) {
    lines->InsertNextCell(static_cast<int>(stretch.size()));
    for (const auto& p : stretch) lines->InsertCellPoint(points->InsertNextPoint(p.position.data()));
  }
  vtkNew<vtkPolyData> path;
  path->SetPoints(points);
  path->SetLines(lines);
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputData(path);
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  actor->GetProperty()->SetColor(0.98, 0.75, 0.20);
  actor->GetProperty()->SetLineWidth(2.0F);
  renderer_->AddActor(actor);
}

void ReviewWindow::fill_metrics() {
  std::vector<std::pair<QString, QString>> rows;
  rows.emplace_back(tr("Result"), score_.passed ? tr("PASSED") : tr("FAILED"));
  rows.emplace_back(tr("Score"), QString::number(score_.score * 100.0, 'f', 1) + " / 100");
  rows.emplace_back(tr("Sensitivity"), QString::fromStdString(score::percent_text(score_.sensitivity)));
  rows.emplace_back(tr("False positives"), QString::number(score_.false_positives));
  QStringList errors;
  for (double e : score_.localization_error_mm) errors << QString::fromStdString(score::mm_text(e));
  rows.emplace_back(tr("Localization error"), errors.isEmpty() ? tr("-") : errors.join(", "));
  rows.emplace_back(tr("Coverage"), QString::fromStdString(score::percent_text(score_.coverage)));
  rows.emplace_back(tr("Deep coverage"), QString::fromStdString(score::percent_text(score_.deep_coverage)));
  rows.emplace_back(tr("Duration (s)"), QString::number(score_.duration_s, 'f', 1));
  rows.emplace_back(tr("Peak force"), QString::fromStdString(score::force_text(score_.peak_force_n)));
  rows.emplace_back(tr("Search pattern"), QString::fromStdString(score::to_string(score_.pattern.kind)));
  for (const auto& g : score_.gates) {
    rows.emplace_back(tr("Gate: %1").arg(QString::fromStdString(g.name)),
                      (g.passed ? tr("pass") : tr("FAIL")) + QString(" (%1 / %2)")
                                                                 .arg(QString::fromStdString(score::gate_value_text(g)),
                                                                      QString::fromStdString(score::gate_threshold_text(g))));
  }
  metrics_->setColumnCount(2);
  metrics_->setRowCount(static_cast<int>(rows.size()));
  metrics_->setHorizontalHeaderLabels({tr("Metric"), tr("Value")});
  metrics_->verticalHeader()->setVisible(false);
  metrics_->setEditTriggers(QAbstractItemView::NoEditTriggers);
  for (int r = 0; r < static_cast<int>(rows.size()); ++r) {
    metrics_->setItem(r, 0, new QTableWidgetItem(rows[static_cast<std::size_t>(r)].first));
    metrics_->setItem(r, 1, new QTableWidgetItem(rows[static_cast<std::size_t>(r)].second));
  }
  metrics_->horizontalHeader()->setSectionResizeMode(0, QHeaderView::ResizeToContents);
  metrics_->horizontalHeader()->setStretchLastSection(true);
}

std::array<double, 3> ReviewWindow::fingertip_centre() const {
  double p[3];
  probe_->GetPosition(p);
  return {p[0], p[1], p[2]};
}

void ReviewWindow::set_time(double t) {
  t_ = std::clamp(t, span_.start, span_.end);
  const double length = span_.end - span_.start;
  const int value = length > 0.0 ? static_cast<int>(std::lround((t_ - span_.start) / length * kSliderSteps)) : 0;
  if (scrubber_->value() != value) {
    const QSignalBlocker block(scrubber_);
    scrubber_->setValue(value);
  }
  if (session_.samples.empty()) {
    probe_->VisibilityOff();
    readout_->setText(tr("t = %1 s (no samples)").arg(t_, 0, 'f', 2));
  } else {
    current_ = session::sample_at(session_.samples, t_);
    const auto& s = session_.samples[current_];
    // The fingertip's tip at the probe point (the recorded position is on or in the tissue).
    probe_->SetPosition(s.position[0], s.position[1], s.position[2] + kFingertipRadius);
    probe_->VisibilityOn();
    readout_->setText(tr("t = %1 s   |F| = %2 N   depth = %3 mm%4")
                          .arg(t_ - span_.start, 0, 'f', 2)
                          .arg(norm(s.force), 0, 'f', 2)
                          .arg(s.depth * 1e3, 0, 'f', 1)
                          .arg(s.body >= 0 ? QString() : tr("   (not in contact)")));
  }
  update_marks();
  charts_->set_cursor(t_);  // moves the cursor only: the series stay as built
  render();
}

void ReviewWindow::render() {
  render_window_->Render();
  since_render_.start();
}

std::size_t ReviewWindow::marks_shown() const { return static_cast<std::size_t>(marks_list_->count()); }

void ReviewWindow::update_marks() {
  // Only redraw when the set of events at or before t changed.
  const auto upto = static_cast<std::size_t>(
      std::upper_bound(session_.events.begin(), session_.events.end(), t_,
                       [](double time, const session::Event& e) { return time < e.t; }) -
      session_.events.begin());
  if (upto == marks_drawn_for_) return;
  marks_drawn_for_ = upto;
  for (auto& actor : mark_actors_) renderer_->RemoveActor(actor);
  mark_actors_.clear();
  marks_list_->clear();
  for (const auto& m : session::marks_at(session_.events, t_)) {
    // The score knows which marks found a tumour (the marks standing at the end): those
    // are drawn green with a line to the tumour's centre, the others red.
    const auto scored = std::find_if(score_.marks.begin(), score_.marks.end(),
                                     [&](const score::MarkResult& r) { return r.id == m.id; });
    const bool hit = scored != score_.marks.end() && scored->tumour >= 0;
    auto actor = hit ? sphere(m.position, kMarkRadius, 0.20, 0.80, 0.30) : sphere(m.position, kMarkRadius, 0.85, 0.10, 0.15);
    renderer_->AddActor(actor);
    mark_actors_.push_back(actor);
    if (hit) {
      const auto& tumour = score_.tumours[static_cast<std::size_t>(scored->tumour)];
      vtkNew<vtkLineSource> line;
      line->SetPoint1(m.position.data());
      line->SetPoint2(tumour.center.data());
      vtkNew<vtkPolyDataMapper> mapper;
      mapper->SetInputConnection(line->GetOutputPort());
      auto link = vtkSmartPointer<vtkActor>::New();
      link->SetMapper(mapper);
      link->GetProperty()->SetColor(0.20, 0.80, 0.30);
      link->GetProperty()->SetLineWidth(3.0F);
      renderer_->AddActor(link);
      mark_actors_.push_back(link);
    }
    marks_list_->addItem(tr("Mark %1 at %2 s").arg(m.id).arg(m.t - span_.start, 0, 'f', 1));
  }
}

void ReviewWindow::play() {
  if (t_ >= span_.end) set_time(span_.start);  // at the end: play from the start
  playing_ = true;
  play_clock_.start();
  play_button_->setText(tr("Pause"));
}

void ReviewWindow::pause() {
  playing_ = false;
  play_button_->setText(tr("Play"));
}

void ReviewWindow::set_speed(double speed) {
  speed_ = std::clamp(speed, 0.25, 8.0);
  const int index = speed_box_->findData(speed_);
  if (index >= 0 && index != speed_box_->currentIndex()) {
    const QSignalBlocker block(speed_box_);
    speed_box_->setCurrentIndex(index);
  }
}

void ReviewWindow::frame() {
  if (playing_) {
    const double elapsed = static_cast<double>(play_clock_.restart()) * 1e-3;
    set_time(t_ + elapsed * speed_);
    if (t_ >= span_.end) pause();
  } else if (!since_render_.isValid() || since_render_.elapsed() >= kIdleRedrawMs) {
    render();
  }
}

bool ReviewWindow::export_report(const std::filesystem::path& dir) {
  try {
    const auto header = report::header_of(session_.info, file_);
    report::write_session_report(dir, file_.stem().string(), header, session_, score_);
  } catch (const std::exception& e) {
    statusBar()->showMessage(tr("Export failed: %1").arg(e.what()));
    return false;
  }
  statusBar()->showMessage(
      tr("Report written: %1").arg(QString::fromStdString((dir / (file_.stem().string() + ".html")).string())));
  return true;
}

void ReviewWindow::choose_export_folder() {
  const QString dir = QFileDialog::getExistingDirectory(this, tr("Export the report into"));
  if (dir.isEmpty()) return;
  // Files already there (an earlier export, or a case named like the session) are replaced
  // only when the user says so.
  QStringList there;
  for (const auto& path : report::session_report_paths(dir.toStdString(), file_.stem().string())) {
    std::error_code ec;
    if (std::filesystem::exists(path, ec)) there << QString::fromStdString(path.filename().string());
  }
  if (!there.isEmpty()) {
    const auto answer = QMessageBox::question(
        this, tr("Replace files?"), tr("%1 already holds %2. Replace them with this report?").arg(dir, there.join(", ")),
        QMessageBox::Yes | QMessageBox::No, QMessageBox::No);
    if (answer != QMessageBox::Yes) return;
  }
  export_report(dir.toStdString());
}

}  // namespace palpa::ui
