#pragma once
// palpa --bench: the graphics frame rate of the paper's Table 1 scenes (1 to 35 bodies) in
// the trainee window at its default size, with the haptic loop at 1 kHz and a scripted
// finger pressing into the bodies (scene::table1_probe), dynamics on and off. Frames are
// drawn as fast as the event loop allows (no 16 ms timer). Needs a QApplication.
#include <filesystem>
#include <optional>

#include "palpa/ui/trainee_window.hpp"

namespace palpa::gui {

struct FrameBenchOptions {
  double seconds = 3.0;                      ///< measured per scene and mode
  int max_bodies = 0;                        ///< only scenes with at most this many bodies (0: all)
  std::optional<std::filesystem::path> csv;  ///< also write the rows here
  bool overlay = true;                       ///< the coverage overlay drawn (as a trainee starts)
  /// Level of detail: the bodies' tolerance on screen, px (TraineeWindow::set_detail_pixels; 0: off).
  double detail_px = ui::TraineeWindow::kDetailPixels;
};

/// Prints the table (stdout) and writes the CSV; returns the process exit code.
int run_frame_bench(const FrameBenchOptions& options);

}  // namespace palpa::gui
