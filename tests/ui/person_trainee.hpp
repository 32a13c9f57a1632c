#pragma once
// A trainee that perceives like a person (docs/perception.md, "The person-like trainee"):
// it works the trainee window only through input events (mouse moves over the view's
// pixels, wheel notches, keys, the Finish button) and reads only what the window shows:
// where the body is on screen (the window's own picking under a pixel, as the eye sees the
// body), the task's words, the push-back trace as drawn and its words, the fingertip and the
// contact ring where they are drawn. It does not know where the tumours are. It remembers a bump by where the
// window's contact ring was when the bump topped (the place on the skin the finger went
// in), not by where the pressed fingertip was drawn: pressed deep into a curved body seen
// at a slant, the fingertip is drawn up to ~10 mm of skin away from that place, and going
// back to where it was drawn would press a different column of tissue.
//
// Its limits: each reading of a bump's height over the trace's baseline, or of a kPa
// figure, carries multiplicative noise of sd kReadingNoise (a 10 % Weber fraction: two
// readings 10 % apart are told apart 75 % of the time); it glances at the trace every
// kGlance seconds; it remembers the trace's last 3 s (what the trace shows) and a few spots
// where a bump stood out. After the guide's strips and the overlay's gaps it goes back to
// its strongest spots at the deep setting and slides across each again, both ways along
// both screen axes (through the middle of what it found); it marks a spot where the four
// strokes bump kConfirm high on average (a slope of the tissue bumps only climbing), no
// more marks than the task names.
#include <QPoint>
#include <deque>
#include <functional>
#include <optional>
#include <random>
#include <vector>

#include "palpa/live/stroke_trace.hpp"
#include "palpa/score/score.hpp"
#include "palpa/ui/trainee_window.hpp"

namespace palpa::test {

class PersonTrainee {
 public:
  static constexpr double kReadingNoise = 0.07;  // sd of ln(reading): 2AFC 75 % at a 10 % difference
  static constexpr double kGlance = 0.25;        // s between glances at the trace
  static constexpr double kCandidate = 1.15;     // a bump this far over the baseline is worth a second look
  static constexpr double kConfirm = 1.10;       // the mean bump of four strokes across a spot, to mark it
  static constexpr int kSpotsKept = 5;           // spots it remembers (the strongest)
  static constexpr double kSpeed = 0.10;         // m/s on the skin: the guide's "about 10 cm a second"
  static constexpr double kStripSpacing = 0.012; // m on the skin between strips (the guide)
  static constexpr double kAcross = 0.035;       // m on the skin before and after a spot it slides across again
  static constexpr double kAcrossLeast = 0.020;  // m: less than this on a side and it does not slide that way
  static constexpr double kSame = 0.015;         // m: bumps closer than this are at one spot
  static constexpr double kBumpSide = 0.030;     // m of stroke each side of a bump's top it reads the lows in
  static constexpr double kFlank = 0.005;        // m of stroke a bump needs each side of its top
  static constexpr double kBumpOver = 0.020;     // m of stroke after a top that ends its bump

  PersonTrainee(ui::TraineeWindow& w, std::uint64_t seed);
  /// The guide's exam: strips at each of `levels` (dial settings), the overlay's gaps at the
  /// last one when it is deep, the second look at its spots, the
  /// marks, Finish. Returns the score.
  score::Score exam(const std::vector<int>& levels);

  struct Spot {
    QPoint px;            // where the contact ring was drawn at the strongest bump seen there
    double salience = 0;  // the sum of the bumps seen there, each perceived height over 1
    int seen = 0;
    double best = 0;      // the strongest bump seen there (perceived)
  };
  const std::vector<Spot>& spots() const { return spots_; }

 private:
  // The window as a person works it.
  std::optional<Vec3> skin_under(const QPoint& px) const;  // the body seen under a pixel
  void move_to(const QPoint& px);
  void wait(double seconds);
  void set_level(int index);
  double now() const;
  QPoint finger_px() const;
  int tumours_asked() const;  // from the task's words: "Find the 2 tumours."
  // The exam's parts.
  std::vector<int> strip_columns(int& top, int& bottom) const;
  struct Bump {
    QPoint px;         // where the contact ring was drawn at the bump's top
    Vec3 at;           // the skin the ring was on
    double perceived;  // its height over the baseline, as read
    double drawn;      // its height over the baseline as drawn (for the log)
  };
  void slide_column(int x, int top, int bottom, bool down);
  void slide(const std::vector<QPoint>& line, const std::function<void(const Bump&)>& felt);
  void fill_overlay_gaps();
  /// A glance at the trace: the bump drawn since the last one, if a whole one was.
  std::optional<Bump> glance();
  std::optional<Bump> judge(const std::deque<live::TracePoint>& points, bool stroke_over);
  void remember(const QPoint& px, double perceived);
  /// The pixel `metres` away on the skin from `from` in screen direction (dx, dy), or the
  /// farthest on the body if that is at least kAcrossLeast; none otherwise.
  std::optional<QPoint> reach(const QPoint& from, double dx, double dy, double metres) const;
  std::optional<Bump> stroke_across(const QPoint& at, const Vec3& spot, double dx, double dy);
  std::optional<QPoint> second_look(const QPoint& at, double& height);
  double perceive(double value);

  ui::TraineeWindow& w_;
  std::mt19937_64 rng_;
  std::vector<Spot> spots_;
  double next_glance_ = 0.0;
  double seen_until_ = -1.0;  // the trace up to here was judged
  std::deque<live::TracePoint> last_trace_;  // the stroke's trace as last seen (judged at its end)
};

}  // namespace palpa::test
