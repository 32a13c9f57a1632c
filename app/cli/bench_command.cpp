// palpa-cli bench SUITE: measured speed against accuracy, with CSV and PNG output.
#include <cstdio>
#include <memory>
#include <vector>

#include "bench_accuracy.hpp"
#include "bench_dynamics.hpp"
#include "bench_fidelity.hpp"
#include "bench_suites.hpp"
#include "bench_table1.hpp"
#include "commands.hpp"
#include "palpa/options/number_checks.hpp"
#include "palpa/io/data_paths.hpp"

namespace palpa::cli {

namespace {

// Each suite is a subcommand of `bench` with its options and what runs it.
Command add_accuracy(CLI::App& bench) {
  auto o = std::make_shared<AccuracyOptions>();
  auto out = std::make_shared<std::string>("bench-results");
  auto* accuracy = bench.add_subcommand(
      "accuracy", "Foot-point search: time per query vs depth error for the paper's bisection (k = 6..20) and the "
                  "fast method (cold, warm) on flat, curved, concave and wavy bodies, against a high-precision "
                  "reference. Writes accuracy.csv and accuracy.png into --out.");
  accuracy->add_option("--probes", o->probes, "probe positions per body (a palpation-like path); default 2000")
      ->check(options::integer_in(10, 1000000));
  accuracy->add_option("--seed", o->seed, "random seed of the paths; default 1")->check(options::integer_in(0, 4294967295));
  accuracy->add_option("--out", *out, "output folder; default bench-results");
  return {accuracy, [o, out] {
            o->out = *out;
            const auto rows = run_accuracy_benchmark(*o);
            std::printf("%-8s %-10s %6s %12s %16s %16s %12s %7s\n", "body", "method", "levels", "ns/query",
                        "depth err max m", "depth err med m", "param err", "inside!");
            for (const auto& r : rows) {
              std::printf("%-8s %-10s %6d %12.0f %16.3e %16.3e %12.3e %7d\n", r.body.c_str(), r.method.c_str(),
                          r.levels, r.ns_per_query, r.depth_error_max, r.depth_error_median, r.param_error_max,
                          r.inside_wrong);
            }
            std::printf("wrote %s and %s\n", (o->out / "accuracy.csv").c_str(), (o->out / "accuracy.png").c_str());
            return static_cast<int>(kOk);
          }};
}

Command add_dynamics(CLI::App& bench) {
  auto out = std::make_shared<std::string>("bench-results");
  auto* dynamics = bench.add_subcommand(
      "dynamics", "Control-point springs: error vs time step for the exact integrator and the Euler family against "
                  "the analytic damped oscillator; landing error, control-point amplification and overshoot for the "
                  "p' x q' choices of control-point modification. Writes dynamics.csv, modification.csv and "
                  "dynamics.png into --out.");
  dynamics->add_option("--out", *out, "output folder; default bench-results");
  return {dynamics, [out] { return run_bench_dynamics(*out); }};
}

Command add_tessellation(CLI::App& bench) {
  auto out = std::make_shared<std::string>("bench-results");
  auto case_path = std::make_shared<std::string>(io::bundled_case_path("default.json").string());
  auto* tessellation = bench.add_subcommand(
      "tessellation", "Display tessellation of a case's first body (top and bottom contours, at rest and pressed "
                      "10 mm in) at tolerances from 1e-2 m to 1e-6 m: segments, triangles, time per body and the "
                      "largest deviation from the surface. Writes tessellation.csv and tessellation.png into --out.");
  tessellation->add_option("--case", *case_path, "case file; default the bundled default.json");
  tessellation->add_option("--out", *out, "output folder; default bench-results");
  return {tessellation, [out, case_path] { return run_bench_tessellation(*out, *case_path); }};
}

Command add_import(CLI::App& bench) {
  auto out = std::make_shared<std::string>("bench-results");
  auto voxels = std::make_shared<int>(256);
  auto points = std::make_shared<int>(317);
  auto* import = bench.add_subcommand(
      "import", "The anatomy import's run time beside its fit error: a 256^3 label volume and a pair of 200 000-"
                "triangle surfaces to a case, and the fit error on grids from 9x11 to 65x65. Writes import.csv into "
                "--out.");
  import->add_option("--voxels", *voxels, "voxels along each side of the volume (256: 1 mm voxels); default 256")
      ->check(CLI::Range(32, 512));
  import->add_option("--mesh-points", *points, "points along each side of the meshes (317: 199 712 triangles); default 317")
      ->check(CLI::Range(16, 1024));
  import->add_option("--out", *out, "output folder; default bench-results");
  return {import, [out, voxels, points] { return run_bench_import(*out, *voxels, *points); }};
}

Command add_contrast_modes(CLI::App& bench) {
  auto out = std::make_shared<std::string>("bench-results");
  auto seed = std::make_shared<std::uint64_t>(7);
  auto* contrast = bench.add_subcommand(
      "contrast-modes", "How clearly the tumour stands out: level mode's force against force mode's stiffness "
                        "(dF/dd), over the tumour and 12 mm away, on default.json and the ladder cases. Writes "
                        "contrast-modes.csv into --out.");
  contrast->add_option("--seed", *seed, "places the tumours; default 7");
  contrast->add_option("--out", *out, "output folder; default bench-results");
  return {contrast, [out, seed] { return run_bench_contrast_modes(*out, *seed); }};
}

Command add_fidelity(CLI::App& bench) {
  auto out = std::make_shared<std::string>("bench-results");
  auto reference_dir = std::make_shared<std::string>();
  auto* fidelity = bench.add_subcommand(
      "fidelity", "Forces against the finite-element reference curves (data/reference: a 7.5 mm flat pad on 20 and "
                  "40 mm layers of 5 kPa on a rigid base, linear and neo-Hookean): the worst force error of the "
                  "calibrated law and of the paper's law up to each curve's reach, and the tumour contrast of "
                  "every inclusion of the on-axis sweep. Writes fidelity.csv, fidelity_contrast.csv and "
                  "fidelity.png into --out; exit 1 if the calibrated law misses a mark (10 % of force; 20 % of "
                  "C - 1 or 0.02 of contrast).");
  fidelity->add_option("--reference", *reference_dir, "folder of the reference CSVs; default the data folder's reference/");
  fidelity->add_option("--out", *out, "output folder; default bench-results");
  return {fidelity, [out, reference_dir] {
            std::filesystem::path reference = *reference_dir;
            if (reference.empty()) {
              try {
                reference = io::find_data_dir(io::this_process_data_search()) / "reference";
              } catch (const io::DataDirError& e) {
                std::fprintf(stderr, "palpa-cli: error: %s\n", e.what());
                return static_cast<int>(kBadInput);
              }
            }
            return run_bench_fidelity(reference, *out);
          }};
}

Command add_table1(CLI::App& bench) {
  auto t1 = std::make_shared<Table1Options>();
  auto csv = std::make_shared<std::string>();
  auto* table1 = bench.add_subcommand(
      "table1", "Scenes like the paper's Table 1 (1/49, 1/105, 4/213, 10/309, 17/465, 35/927 bodies/MAT points): "
                "preprocessing time, model memory, haptic step time p50/p99 with and without dynamics, the highest "
                "sustainable rate and the share of one core at 1 kHz, printed beside the paper's figures.");
  table1->add_option("--csv", *csv, "also write the figures as CSV");
  table1->add_option("--seconds", t1->seconds, "simulated seconds of palpation per scene and mode; default 2")
      ->check(options::finite_in(0.1, 600.0, "s"));
  table1->add_option("--realtime-seconds", t1->realtime_seconds,
                     "then run each scene paced at 1 kHz on the real-time thread this long (0: skip); default 2")
      ->check(options::finite_in(0.0, 3600.0, "s"));
  table1->add_flag("--load", t1->load, "keep every core busy with other threads during the paced runs");
  table1->add_option("--display-span", t1->display_span,
                     "m: knot spans of the drawn surfaces (display refinement); 0 draws the fitted nets; default 0.004")
      ->check(options::finite_in(0.0, 1.0, "m"));
  auto tissue = std::make_shared<std::string>("nm");
  auto indenter = std::make_shared<std::string>("pad");
  table1->add_option("--tissue", *tissue,
                     "nm: the paper's springs in N/m (default); kpa: every body given by the modulus that derives the "
                     "same stiffness, under the calibrated law")
      ->check(CLI::IsMember({"nm", "kpa"}));
  table1->add_option("--indenter", *indenter, "pad (default) or finger: what presses bodies in kPa")
      ->check(CLI::IsMember({"pad", "finger"}));
  return {table1, [t1, csv, tissue, indenter] {
            if (!csv->empty()) t1->csv = *csv;
            t1->tissue_in_pa = *tissue == "kpa";
            t1->finger = *indenter == "finger";
            if (t1->finger && !t1->tissue_in_pa) {
              std::fprintf(stderr, "palpa-cli: error: --indenter finger needs --tissue kpa (the paper's springs have no "
                                   "indenter)\n");
              return static_cast<int>(kBadInput);
            }
            return run_bench_table1(*t1);
          }};
}

}  // namespace

Command add_bench_command(CLI::App& parent) {
  auto* app = parent.add_subcommand("bench", "Benchmarks that report run time together with the error it buys.");
  app->require_subcommand(1);
  const std::vector<Command> suites = {add_accuracy(*app), add_dynamics(*app), add_tessellation(*app),
                                       add_fidelity(*app), add_table1(*app), add_contrast_modes(*app),
                                       add_import(*app)};
  return {app, [suites] {
            for (const auto& suite : suites)
              if (suite.app->parsed()) return suite.run();
            return static_cast<int>(kBadInput);
          }};
}

}  // namespace palpa::cli
