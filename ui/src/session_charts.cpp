#include "palpa/ui/session_charts.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <QLabel>
#include <QVBoxLayout>
#include <vtkAxis.h>
#include <vtkChartXY.h>
#include <vtkContextScene.h>
#include <vtkContextView.h>
#include <vtkDoubleArray.h>
#include <vtkGenericOpenGLRenderWindow.h>
#include <vtkPen.h>
#include <vtkPlotLine.h>
#include <vtkRenderWindowInteractor.h>
#include <vtkRenderer.h>
#include <vtkTable.h>
#include <vtkTextProperty.h>

#include "palpa/mat/mat_body.hpp"
#include "palpa/ui/vtk_view.hpp"

namespace palpa::ui {
namespace {

// Colours (RGB 0-255). The depth levels are the pressure map's ColorBrewer Blues
// (report::level_colour), the lightest one darkened to stand out on white.
constexpr unsigned char kForce[3] = {128, 0, 160};
constexpr unsigned char kMark[3] = {40, 150, 40};
constexpr unsigned char kLimit[3] = {220, 30, 30};
constexpr unsigned char kCursor[3] = {0, 0, 0};
constexpr unsigned char kLevel[4][3] = {{150, 150, 150}, {140, 190, 225}, {66, 146, 198}, {8, 69, 148}};
constexpr const char* kLevelName[4] = {"depth: no contact", "depth: light", "depth: medium", "depth: deep"};

vtkSmartPointer<vtkTable> table(const std::vector<std::string>& columns) {
  auto out = vtkSmartPointer<vtkTable>::New();
  for (const auto& name : columns) {
    vtkNew<vtkDoubleArray> column;
    column->SetName(name.c_str());
    out->AddColumn(column);
  }
  return out;
}

void add_row(vtkTable* t, std::initializer_list<double> values) {
  vtkIdType c = 0;
  for (const double v : values) vtkDoubleArray::SafeDownCast(t->GetColumn(c++))->InsertNextValue(v);
}

/// Indices of the samples kept from y: the smallest and the largest of each bucket, in
/// time order, at most `max_points` in all; the first and last samples are always kept (the
/// series spans the session).
std::vector<std::size_t> min_max_decimate(const std::vector<double>& y, std::size_t max_points) {
  std::vector<std::size_t> kept;
  const std::size_t n = y.size();
  if (n == 0) return kept;
  const std::size_t buckets = std::max<std::size_t>(1, (max_points - 2) / 2);
  const std::size_t run = std::max<std::size_t>(1, (n + buckets - 1) / buckets);
  for (std::size_t begin = 0; begin < n; begin += run) {
    const std::size_t end = std::min(n, begin + run);
    std::size_t lo = begin, hi = begin;
    for (std::size_t i = begin + 1; i < end; ++i) {
      if (y[i] < y[lo]) lo = i;
      if (y[i] > y[hi]) hi = i;
    }
    for (const std::size_t i : {begin, std::min(lo, hi), std::max(lo, hi), end - 1}) {
      const bool edge = i == 0 || i == n - 1;
      if ((edge || i == lo || i == hi) && (kept.empty() || kept.back() < i)) kept.push_back(i);
    }
  }
  return kept;
}

vtkPlot* add_line(vtkChartXY* chart, vtkTable* data, const char* y, const unsigned char rgb[3], float width,
                  int corner = 0) {
  auto* plot = chart->AddPlot(vtkChart::LINE);
  plot->SetInputData(data, "t (s)", y);
  plot->SetColor(rgb[0], rgb[1], rgb[2], 255);
  plot->SetWidth(width);
  if (corner != 0) chart->SetPlotCorner(plot, corner);
  return plot;
}

void fix_axis(vtkAxis* axis, double lo, double hi, const char* title) {
  axis->SetBehavior(vtkAxis::FIXED);
  axis->SetRange(lo, hi);
  axis->SetTitle(title);
  axis->GetTitleProperties()->SetFontSize(11);
  axis->GetLabelProperties()->SetFontSize(10);
}

}  // namespace

SessionCharts::SessionCharts(const session::Session& session, const score::Score& score, const scene::Scene* scene,
                             session::TimeSpan span, QWidget* parent)
    : QWidget(parent), span_(span), cursor_t_(span.start) {
  auto* layout = new QVBoxLayout(this);
  layout->setContentsMargins(0, 0, 0, 0);
  layout->setSpacing(2);
  view_ = new VtkView(this);
  layout->addWidget(view_, 1);
  legend_ = new QLabel(this);
  legend_->setTextFormat(Qt::RichText);
  const auto css = [](const unsigned char c[3]) { return QString("rgb(%1,%2,%3)").arg(c[0]).arg(c[1]).arg(c[2]); };
  legend_->setText(tr("<span style='color:%1'>&#9644; |F| (N, right)</span> &nbsp; depth (mm, left): "
                      "<span style='color:%2'>&#9644; light</span> <span style='color:%3'>&#9644; medium</span> "
                      "<span style='color:%4'>&#9644; deep</span> &nbsp; <span style='color:%5'>&#9482; mark</span>"
                      " &nbsp; <span style='color:%6'>&#9482; safety limit</span> &nbsp; "
                      "<span style='color:%7'>&#9475; replay time</span> &nbsp; (click to seek)")
                       .arg(css(kForce), css(kLevel[1]), css(kLevel[2]), css(kLevel[3]), css(kMark), css(kLimit),
                            css(kCursor)));
  legend_->setWordWrap(true);  // a narrow window (a small screen) gets two lines, not a wider window
  layout->addWidget(legend_);

  render_window_ = vtkSmartPointer<vtkGenericOpenGLRenderWindow>::New();
  render_window_->SetMultiSamples(0);  // software OpenGL: see TraineeWindow
  view_->setRenderWindow(render_window_);
  context_ = vtkSmartPointer<vtkContextView>::New();
  context_->SetRenderWindow(render_window_);
  context_->SetInteractor(view_->interactor());
  context_->GetRenderer()->SetBackground(1.0, 1.0, 1.0);
  chart_ = vtkSmartPointer<vtkChartXY>::New();
  context_->GetScene()->AddItem(chart_);
  // The time axis is the replay's: no panning or zooming it away; a left click seeks.
  for (const int action : {vtkChart::PAN, vtkChart::ZOOM, vtkChart::ZOOM_AXIS, vtkChart::SELECT}) {
    chart_->SetActionToButton(action, -1);
  }
  chart_->SetZoomWithMouseWheel(false);
  press_observer_ = view_->interactor()->AddObserver(vtkCommand::LeftButtonPressEvent, this, &SessionCharts::on_press);
  build(session, score, scene);
}

SessionCharts::~SessionCharts() {
  if (view_->interactor() != nullptr) view_->interactor()->RemoveObserver(press_observer_);
}

void SessionCharts::build(const session::Session& session, const score::Score& score, const scene::Scene* scene) {
  const auto& samples = session.samples;
  const std::size_t n = samples.size();
  std::vector<double> force(n), depth_mm(n, 0.0);
  double peak = 0.0, deepest = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const auto& s = samples[i];
    force[i] = std::sqrt(s.force[0] * s.force[0] + s.force[1] * s.force[1] + s.force[2] * s.force[2]);
    if (s.body >= 0 && s.depth > 0.0) depth_mm[i] = s.depth * 1e3;
    peak = std::max(peak, force[i]);
    deepest = std::max(deepest, depth_mm[i]);
  }
  // Pressure level of a sample: depth over the local tissue thickness (2 R), as scored.
  const auto level_of = [&](const engine::Sample& s) -> int {
    if (s.body < 0) return 0;
    if (scene == nullptr || static_cast<std::size_t>(s.body) >= scene->size()) return 1;
    double channels[4];
    scene->body(static_cast<std::size_t>(s.body))
        .body.skeleton()
        .evaluate(std::clamp(s.u, 0.0, 1.0), std::clamp(s.v, 0.0, 1.0), channels, 4);
    const double thickness = 2.0 * channels[mat::kRadius];
    const double level = thickness > 0.0 ? std::max(0.0, s.depth) / thickness : 0.0;
    return level >= score.thresholds.deep_min ? 3 : level >= score.thresholds.light_max ? 2 : 1;
  };

  force_ = table({"t (s)", "|F| (N)"});
  for (const std::size_t i : min_max_decimate(force, kMaxPoints)) add_row(force_, {samples[i].t - span_.start, force[i]});
  // VTK's line plots have one colour: the depth line is drawn as separate segments, one
  // series per pressure level, each segment in the deeper level of its two ends. Segment
  // pairs (not NaN gaps) keep it to one draw call per level: a NaN-split series costs one
  // call per piece, which made a frame several times slower under software OpenGL.
  depth_ = table({"t (s)", "depth (mm)", "level"});
  const auto kept = min_max_decimate(depth_mm, kMaxPoints);
  std::vector<int> levels(kept.size());
  for (std::size_t k = 0; k < kept.size(); ++k) {
    levels[k] = level_of(samples[kept[k]]);
    add_row(depth_, {samples[kept[k]].t - span_.start, depth_mm[kept[k]], static_cast<double>(levels[k])});
  }
  for (int l = 0; l < 4; ++l) level_segments_[l] = table({"t (s)", kLevelName[l]});
  for (std::size_t k = 0; k + 1 < kept.size(); ++k) {
    auto* segments = level_segments_[std::max(levels[k], levels[k + 1])].Get();
    for (const std::size_t j : {k, k + 1}) add_row(segments, {samples[kept[j]].t - span_.start, depth_mm[kept[j]]});
  }

  const bool show_limit = peak > 0.5 * score.thresholds.max_force;
  force_top_ = std::max({1.0, peak * 1.08, show_limit ? score.thresholds.max_force * 1.05 : 0.0});
  const double duration = std::max(span_.end - span_.start, 1e-3);
  marks_ = table({"t (s)", "marker"});
  for (const auto& e : session.events) {
    if (e.kind != session::EventKind::Mark) continue;
    add_row(marks_, {e.t - span_.start, 0.0});
    add_row(marks_, {e.t - span_.start, force_top_});
  }
  cursor_ = table({"t (s)", "cursor"});
  add_row(cursor_, {0.0, 0.0});
  add_row(cursor_, {0.0, force_top_});
  limit_ = table({"t (s)", "limit"});
  add_row(limit_, {0.0, score.thresholds.max_force});
  add_row(limit_, {duration, score.thresholds.max_force});

  add_plots(show_limit, duration, deepest);
  set_cursor(span_.start);
}

// The lines over the tables and the axes: depth on the left axis (corner 0), the force and
// the lines in newtons on the right (corner 1).
void SessionCharts::add_plots(bool show_limit, double duration, double deepest_mm) {
  // vtkChartXY draws corner by corner, so the force line stays on top.
  for (int l = 0; l < 4; ++l) {
    auto* level = vtkPlotLine::SafeDownCast(add_line(chart_, level_segments_[l], kLevelName[l], kLevel[l], 1.0F));
    level->PolyLineOff();
  }
  add_line(chart_, force_, "|F| (N)", kForce, 1.0F, 1);
  auto* marks = vtkPlotLine::SafeDownCast(add_line(chart_, marks_, "marker", kMark, 1.5F, 1));
  marks->PolyLineOff();  // one segment per pair of rows
  marks->GetPen()->SetLineType(vtkPen::DASH_LINE);
  if (show_limit) {
    auto* limit = add_line(chart_, limit_, "limit", kLimit, 1.5F, 1);
    limit->GetPen()->SetLineType(vtkPen::DASH_LINE);
  }
  add_line(chart_, cursor_, "cursor", kCursor, 2.0F, 1);

  fix_axis(chart_->GetAxis(vtkAxis::BOTTOM), 0.0, duration, "time (s)");
  fix_axis(chart_->GetAxis(vtkAxis::LEFT), 0.0, std::max(1.0, deepest_mm * 1.08), "depth (mm)");
  fix_axis(chart_->GetAxis(vtkAxis::RIGHT), 0.0, force_top_, "|F| (N)");
  chart_->SetShowLegend(false);  // the Qt legend under the view names the colours
}

vtkChartXY* SessionCharts::chart() const { return chart_; }
vtkTable* SessionCharts::force_table() const { return force_; }
vtkTable* SessionCharts::depth_table() const { return depth_; }
vtkTable* SessionCharts::mark_table() const { return marks_; }
vtkTable* SessionCharts::cursor_table() const { return cursor_; }

std::size_t SessionCharts::mark_markers() const { return static_cast<std::size_t>(marks_->GetNumberOfRows() / 2); }

void SessionCharts::set_cursor(double t) {
  cursor_t_ = std::clamp(t, span_.start, span_.end);
  const double x = cursor_t_ - span_.start;
  auto* column = vtkDoubleArray::SafeDownCast(cursor_->GetColumn(0));
  column->SetValue(0, x);
  column->SetValue(1, x);
  column->Modified();
  cursor_->Modified();
  // A chart frame costs about as much as the 3-D view's under software OpenGL; the cursor
  // moves one pixel per ~0.15 s of a two-minute session, so redraw only when it would land
  // on another pixel column (the new value shows at the next redraw in any case).
  const int pixel = cursor_pixel();
  if (pixel >= 0 && pixel == drawn_pixel_) return;
  drawn_pixel_ = pixel;
  render_window_->Render();
}

int SessionCharts::cursor_pixel() const {
  auto* axis = chart_->GetAxis(vtkAxis::BOTTOM);
  const double left = static_cast<double>(axis->GetPoint1()[0]);
  const double right = static_cast<double>(axis->GetPoint2()[0]);
  const double range = axis->GetMaximum() - axis->GetMinimum();
  if (!(right > left) || !(range > 0.0)) return -1;  // not drawn yet
  return static_cast<int>(std::lround(left + (cursor_t_ - span_.start - axis->GetMinimum()) / range * (right - left)));
}

double SessionCharts::time_at(QPoint pixel) const {
  // The axis' ends are in scene coordinates: device pixels, y up.
  auto* axis = chart_->GetAxis(vtkAxis::BOTTOM);
  const double left = static_cast<double>(axis->GetPoint1()[0]);
  const double right = static_cast<double>(axis->GetPoint2()[0]);
  if (!(right > left)) return span_.start;
  const double x = pixel.x() * view_->devicePixelRatioF();
  const double f = std::clamp((x - left) / (right - left), 0.0, 1.0);
  return span_.start + axis->GetMinimum() + f * (axis->GetMaximum() - axis->GetMinimum());
}

void SessionCharts::on_press() {
  const int* at = view_->interactor()->GetEventPosition();
  const double dpr = view_->devicePixelRatioF();
  emit seek_requested(time_at(QPoint(static_cast<int>(at[0] / dpr), static_cast<int>(at[1] / dpr))));
}

}  // namespace palpa::ui
