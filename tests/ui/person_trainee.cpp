// The person-like trainee (person_trainee.hpp, docs/perception.md).
#include "person_trainee.hpp"

#include <QApplication>
#include <QLabel>
#include <QMouseEvent>
#include <QPushButton>
#include <QRegularExpression>
#include <QWheelEvent>
#include <QWindow>
#include <QtTest>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <functional>

#include "palpa/live/live_coverage.hpp"
#include "palpa/live/stroke_trace.hpp"
#include "palpa/ui/push_back_trace.hpp"
#include "palpa/ui/vtk_view.hpp"

namespace palpa::test {

namespace {
constexpr int kSurveyStep = 4;  // px between the survey's looks at the view
constexpr double kEdge = 0.003; // m: the outermost strips run this close to the rim
constexpr int kSecondLooks = 4; // spots looked at again, strongest first
}  // namespace

PersonTrainee::PersonTrainee(ui::TraineeWindow& w, std::uint64_t seed) : w_(w), rng_(seed) {}

std::optional<Vec3> PersonTrainee::skin_under(const QPoint& px) const {
  const auto [near, far] = w_.view()->pointer_ray(*w_.renderer(), px);
  const auto hit = w_.exercise().pick(near, far - near);
  if (!hit) return std::nullopt;
  return hit->point;
}

void PersonTrainee::move_to(const QPoint& px) {
  QWindow* view = w_.view()->input();
  QMouseEvent e(QEvent::MouseMove, px, view->mapToGlobal(px), Qt::NoButton, Qt::NoButton, Qt::NoModifier);
  QApplication::sendEvent(view, &e);
}

void PersonTrainee::wait(double seconds) { QTest::qWait(static_cast<int>(seconds * 1000.0)); }

double PersonTrainee::now() const { return w_.exercise().snapshot().t; }

void PersonTrainee::set_level(int index) {
  QWindow* view = w_.view()->input();
  const QPoint px(view->width() / 2, view->height() / 2);
  while (w_.pressure().index() != index) {
    const int notch = w_.pressure().index() < index ? 1 : -1;
    QWheelEvent e(QPointF(px), QPointF(view->mapToGlobal(px)), QPoint(), QPoint(0, 120 * notch), Qt::NoButton,
                  Qt::NoModifier, Qt::NoScrollPhase, false);
    QApplication::sendEvent(view, &e);
  }
}

QPoint PersonTrainee::finger_px() const {
  const auto& s = w_.exercise().snapshot();
  return w_.to_view(Vec3(s.probe[0], s.probe[1], s.probe[2]));
}

int PersonTrainee::tumours_asked() const {
  for (const auto* label : w_.findChildren<QLabel*>()) {
    const QString t = label->text();
    if (t.contains("Find the tumour.")) return 1;
    const auto m = QRegularExpression("Find the (\\d+) tumours").match(t);
    if (m.hasMatch()) return m.captured(1).toInt();
  }
  return 0;  // "Is there a tumour?"
}

double PersonTrainee::perceive(double value) {
  std::normal_distribution<double> noise(0.0, kReadingNoise);
  return value * std::exp(noise(rng_));
}

// The columns of the guide's strips on screen, left to right, kStripSpacing apart on the
// skin wherever both have skin; `top`, `bottom`: the rows the body spans.
std::vector<int> PersonTrainee::strip_columns(int& top, int& bottom) const {
  QWindow* view = w_.view()->input();
  int left = view->width(), right = -1;
  top = view->height(), bottom = -1;
  for (int x = 0; x < view->width(); x += kSurveyStep)
    for (int y = 0; y < view->height(); y += kSurveyStep)
      if (skin_under({x, y})) left = std::min(left, x), right = std::max(right, x), top = std::min(top, y), bottom = std::max(bottom, y);
  if (right < left) return {};
  const auto gap = [&](int xa, int xb) {
    double worst = 0.0;
    for (int y = top; y <= bottom; y += 2 * kSurveyStep) {
      const auto a = skin_under({xa, y}), b = skin_under({xb, y});
      if (a && b) worst = std::max(worst, (*a - *b).norm());
    }
    return worst;
  };
  int first = left;
  while (first < right && gap(left, first) < kEdge) ++first;
  std::vector<int> xs{first};
  while (xs.back() < right) {
    int step = 1;
    while (xs.back() + step + 1 <= right && gap(xs.back(), xs.back() + step + 1) <= kStripSpacing) ++step;
    xs.push_back(xs.back() + step);
  }
  return xs;
}

void PersonTrainee::slide_column(int x, int top, int bottom, bool down) {
  std::vector<QPoint> line;
  for (int k = 0; k <= bottom - top; k += 2) line.emplace_back(x, down ? top + k : bottom - k);
  slide(line, [this](const Bump& b) {
    if (b.perceived >= kCandidate) remember(b.px, b.perceived);
  });
}

// Along `line` (view pixels, from its first to its last on the body) at kSpeed on the skin.
void PersonTrainee::slide(const std::vector<QPoint>& line, const std::function<void(const Bump&)>& felt) {
  struct Stop {
    QPoint px;
    double along;
  };
  std::vector<Stop> stops;
  std::optional<Vec3> last;
  double along = 0.0;
  for (const QPoint& px : line) {
    const auto skin = skin_under(px);
    if (skin && last) along += (*skin - *last).norm();
    if (skin) last = skin;
    if (skin || !stops.empty()) stops.push_back({px, along});
  }
  while (!stops.empty() && !skin_under(stops.back().px)) stops.pop_back();
  if (stops.empty()) return;
  const double t0 = now();
  for (std::size_t at = 0;;) {
    const double s = (now() - t0) * kSpeed;
    while (at + 1 < stops.size() && stops[at + 1].along <= s) ++at;
    move_to(stops[at].px);
    if (const auto bump = glance()) felt(*bump);
    if (!w_.push_back_trace()->trace().points().empty()) last_trace_ = w_.push_back_trace()->trace().points();
    if (at + 1 >= stops.size()) break;
    QTest::qWait(10);
  }
  // The stroke's end: what the last seconds showed (the rim may have cleared the trace).
  wait(0.2);
  if (!w_.push_back_trace()->trace().points().empty()) last_trace_ = w_.push_back_trace()->trace().points();
  if (const auto bump = judge(last_trace_, true)) felt(*bump);
}

// A look at the trace (the last 3 s as drawn), kGlance after the last one.
std::optional<PersonTrainee::Bump> PersonTrainee::glance() {
  if (now() < next_glance_) return std::nullopt;
  next_glance_ = now() + kGlance;
  return judge(w_.push_back_trace()->trace().points(), false);
}

// A bump in `points` not judged before: a top (the firmest point within kFlank of stroke
// either side) that has come down again by three quarters of what it rose, or that the
// stroke left kBumpOver behind, or (`stroke_over`) that has kFlank of stroke after it. Its
// height is read as one reads a chart: the top over the mean of the lows on either side
// (within kBumpSide of stroke). A rise the stroke ends in (toward the rim) is no bump. Of
// the bumps, the highest.
std::optional<PersonTrainee::Bump> PersonTrainee::judge(const std::deque<live::TracePoint>& points, bool stroke_over) {
  std::optional<std::pair<double, std::size_t>> best;  // height as drawn, top
  double judged = seen_until_;
  for (std::size_t k = 0; k < points.size(); ++k) {
    const auto& top = points[k];
    if (top.t <= seen_until_ || top.along < kFlank) continue;
    double left = top.firmness, right = top.firmness;
    bool is_top = true, fell = false;
    for (std::size_t j = 0; j < points.size() && is_top; ++j) {
      const double d = points[j].along - top.along;
      if (std::abs(d) <= kFlank && points[j].firmness > top.firmness) is_top = false;
      if (j < k && -d <= kBumpSide) left = std::min(left, points[j].firmness);
    }
    if (!is_top || !(top.firmness > left)) continue;
    for (std::size_t j = k + 1; j < points.size(); ++j) {
      const double after = points[j].along - top.along;
      if (after > kBumpSide) break;
      right = std::min(right, points[j].firmness);
      const bool down = top.firmness - right >= 0.75 * (top.firmness - left) && after >= kFlank;
      if (!fell && (down || after >= kBumpOver || (stroke_over && after >= kFlank))) fell = true, judged = std::max(judged, points[j].t);
    }
    const double drawn = top.firmness / (0.5 * (left + right));
    if (fell && (!best || drawn > best->first)) best = {drawn, k};
  }
  if (stroke_over && !points.empty()) judged = std::max(judged, points.back().t);
  seen_until_ = judged;
  if (!best) return std::nullopt;
  const auto& top = points[best->second];
  return Bump{w_.to_view(top.skin), top.skin, perceive(best->first), best->first};
}

void PersonTrainee::remember(const QPoint& px, double perceived) {
  const auto here = skin_under(px);
  if (!here) return;
  for (auto& s : spots_) {
    const auto there = skin_under(s.px);
    if (!there || (*there - *here).norm() > kSame) continue;
    s.salience += perceived - 1.0;
    ++s.seen;
    if (perceived > s.best) s.best = perceived, s.px = px;
    std::sort(spots_.begin(), spots_.end(), [](const Spot& a, const Spot& b) { return a.salience > b.salience; });
    return;
  }
  spots_.push_back({px, perceived - 1.0, 1, perceived});
  // A person keeps a handful: the faintest is forgotten.
  std::sort(spots_.begin(), spots_.end(), [](const Spot& a, const Spot& b) { return a.salience > b.salience; });
  if (spots_.size() > static_cast<std::size_t>(kSpotsKept)) spots_.pop_back();
}

std::optional<QPoint> PersonTrainee::reach(const QPoint& from, double dx, double dy, double metres) const {
  const auto start = skin_under(from);
  std::optional<QPoint> last;
  for (int k = 1; k < 600 && start; ++k) {
    const QPoint px(from.x() + static_cast<int>(std::lround(k * dx)), from.y() + static_cast<int>(std::lround(k * dy)));
    const auto skin = skin_under(px);
    if (!skin) break;
    last = px;
    if ((*skin - *start).norm() >= metres) return px;
  }
  // The body ends first: as far as it goes, if that leaves the trace room to settle.
  if (last && (*skin_under(*last) - *start).norm() >= kAcrossLeast) return last;
  return std::nullopt;
}

// One stroke across `spot` (seen at pixel `at`) in screen direction (dx, dy), kAcross
// before it to kAcross after it on the skin (less where the body ends, but at least
// kAcrossLeast, so that the trace has settled): the highest bump within kSame of the spot.
std::optional<PersonTrainee::Bump> PersonTrainee::stroke_across(const QPoint& at, const Vec3& spot, double dx, double dy) {
  const auto from = reach(at, -dx, -dy, kAcross), to = reach(at, dx, dy, kAcross);
  if (!from || !to) {
    qInfo("    across (%+.0f, %+.0f): the body ends too soon", dx, dy);
    return std::nullopt;
  }
  std::vector<QPoint> line;
  const QPoint step = *to - *from;
  const int n = std::max({std::abs(step.x()), std::abs(step.y()), 1});
  for (int k = 0; k <= n; ++k) line.emplace_back(from->x() + step.x() * k / n, from->y() + step.y() * k / n);
  move_to(*from);
  wait(0.5);  // a jump: a new stroke from here
  std::optional<Bump> best;
  const auto near = [&](const Bump& b) {
    if ((b.at - spot).norm() <= kSame && (!best || b.perceived > best->perceived)) best = b;
  };
  slide(line, near);
  if (std::getenv("PALPA_PERSON_DEBUG")) {
    QString row;
    double last = -1.0;
    for (const auto& p : last_trace_) {
      if (p.along - last < 0.003) continue;
      last = p.along;
      row += QString(" %1:%2(%3)").arg(std::lround(1e3 * p.along)).arg(p.firmness * 1e-3, 0, 'f', 2).arg(std::lround(1e3 * (p.skin - spot).norm()));
    }
    qInfo("      trace (mm along: kPa (mm from the spot)):%s", qPrintable(row));
  }
  return best;
}

// Back at a spot: slides across it again, left to right and back, then down and up through
// the middle of what the first two found. A lump bumps near the spot in every direction; a
// slope of the tissue (firmer toward one side) bumps only climbing and dips coming down. The
// lump's middle (across, where the side-to-side strokes topped; down, where the up-and-down
// ones did) when the four strokes' bumps average kConfirm high, a stroke without a bump
// near the spot counting as none (1); `height`: that average.
std::optional<QPoint> PersonTrainee::second_look(const QPoint& at, double& height) {
  auto spot = skin_under(at);
  if (!spot) return std::nullopt;
  QPoint centre = at;
  height = 0.0;
  int found_any = 0;
  for (const bool across : {true, false}) {
    double middle = 0.0;
    int found = 0;
    for (const double sign : {1.0, -1.0}) {
      const auto b = stroke_across(centre, *spot, across ? sign : 0.0, across ? 0.0 : sign);
      qInfo("    %s: %s", across ? (sign > 0 ? "left to right" : "right to left") : (sign > 0 ? "down" : "up"),
            b ? qPrintable(QString("a bump %1 % (drawn %2 %) %3 mm from the spot").arg(std::lround(100 * (b->perceived - 1)))
                               .arg(std::lround(100 * (b->drawn - 1))).arg(std::lround(1e3 * (b->at - *spot).norm())))
              : "no bump near the spot");
      height += b ? std::max(1.0, b->perceived) : 1.0;
      if (b) middle += across ? b->px.x() : b->px.y(), ++found;
    }
    if (found == 0) continue;
    found_any += found;
    // Through the middle of what this pair found, for the other direction (and the mark).
    const QPoint moved = across ? QPoint(static_cast<int>(std::lround(middle / found)), centre.y())
                                : QPoint(centre.x(), static_cast<int>(std::lround(middle / found)));
    if (const auto skin = skin_under(moved)) centre = moved, spot = skin;
  }
  height /= 4.0;
  if (height < kConfirm || found_any == 0) return std::nullopt;
  return centre;
}

void PersonTrainee::fill_overlay_gaps() {
  const auto& cover = w_.live_coverage();
  std::vector<QPoint> tried;
  QPoint at = finger_px();
  for (int visited = 0; visited < 300; ++visited) {
    std::vector<QPoint> open;
    for (std::size_t b = 0; b < cover.bodies(); ++b)
      for (std::size_t k = 0; k < cover.levels(b).size(); ++k)
        if (cover.areas(b)[k] > 0.0 && cover.levels(b)[k] < 3) {
          const QPoint px = w_.to_view(cover.centers(b)[k]);
          if (std::none_of(tried.begin(), tried.end(), [&](const QPoint& t) { return (t - px).manhattanLength() < 8; }))
            open.push_back(px);
        }
    if (open.empty()) return;
    at = *std::min_element(open.begin(), open.end(),
                           [&](const QPoint& a, const QPoint& b) { return (a - at).manhattanLength() < (b - at).manhattanLength(); });
    tried.push_back(at);
    move_to(at);
    wait(0.3);
  }
}

score::Score PersonTrainee::exam(const std::vector<int>& levels) {
  int top = 0, bottom = 0;
  const auto columns = strip_columns(top, bottom);
  const int light = live::PressureDial::middle_of(live::PressureLevel::Light);
  for (const int level : levels) {
    set_level(light);
    move_to({columns.front(), top});
    wait(0.6);
    set_level(level);
    bool down = true;
    for (const int x : columns) {
      slide_column(x, top, bottom, down);
      down = !down;
    }
  }
  const bool deep = live::PressureDial(w_.exercise().thresholds(), levels.back()).level() == live::PressureLevel::Deep;
  if (deep) fill_overlay_gaps();
  std::vector<std::pair<double, QPoint>> marks;
  set_level(levels.back());  // the second look at the pass's deepest setting, where a lump stands out most
  for (int k = 0; k < std::min<int>(kSecondLooks, static_cast<int>(spots_.size())); ++k) {
    double height = 0.0;
    const auto& spot = spots_[static_cast<std::size_t>(k)];
    const auto m = second_look(spot.px, height);
    if (m) marks.emplace_back(height, *m);
    const Vec3 at = skin_under(spot.px).value_or(Vec3::Zero());
    qInfo("  second look %d at (%.0f, %.0f, %.0f) mm: seen %d times (salience %.2f)%s", k + 1, 1e3 * at.x(),
          1e3 * at.y(), 1e3 * at.z(), spot.seen, spot.salience,
          m ? qPrintable(QString(": a lump, bumps %1 % high across it").arg(std::lround(100 * (height - 1)))) : ": nothing across it");
  }
  std::sort(marks.begin(), marks.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
  std::vector<Vec3> placed;
  const int most = std::max(1, tumours_asked());
  for (const auto& [ratio, px] : marks) {
    const auto skin = skin_under(px);
    if (!skin || static_cast<int>(placed.size()) >= most) continue;
    if (std::any_of(placed.begin(), placed.end(), [&](const Vec3& p) { return (p - *skin).norm() < 0.025; })) continue;
    placed.push_back(*skin);
    // The mark goes where the finger is: at medium it is over the spot, not pressed along a
    // column deep under a curved body.
    set_level(live::PressureDial::middle_of(live::PressureLevel::Medium));
    move_to(px);
    wait(0.8);
    QTest::keyClick(&w_, Qt::Key_M);
  }
  for (auto* b : w_.findChildren<QPushButton*>())
    if (b->text().startsWith("Finish")) QTest::mouseClick(b, Qt::LeftButton);
  return w_.score().value_or(score::Score{});
}

}  // namespace palpa::test
