#pragma once
// CSV output of simulated haptic ticks (palpa-cli simulate --out; --session records a session file).
#include <cstdio>
#include <string>

#include "palpa/engine/engine.hpp"
#include "palpa/engine/virtual_device.hpp"

namespace palpa::cli {

/// Writes samples as `t,x,y,z,fx,fy,fz,body,u,v,depth,buttons,overrun,fault` with
/// round-trip precision, so equal runs give equal bytes.
class SampleCsvWriter {
 public:
  explicit SampleCsvWriter(const std::string& path);
  ~SampleCsvWriter();
  SampleCsvWriter(const SampleCsvWriter&) = delete;
  SampleCsvWriter& operator=(const SampleCsvWriter&) = delete;
  bool ok() const { return file_ != nullptr; }
  void write(const engine::Sample& s, const std::string& body_id);
  bool close();

 private:
  std::FILE* file_;
  bool failed_ = false;
};

bool write_marks_csv(const std::string& path, const engine::Trajectory& marks);

}  // namespace palpa::cli
