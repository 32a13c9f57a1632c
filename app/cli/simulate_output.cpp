#include "simulate_output.hpp"

namespace palpa::cli {

SampleCsvWriter::SampleCsvWriter(const std::string& path) : file_(std::fopen(path.c_str(), "wb")) {
  if (file_ != nullptr && std::fputs("t,x,y,z,fx,fy,fz,body,u,v,depth,buttons,overrun,fault\n", file_) < 0) failed_ = true;
}

SampleCsvWriter::~SampleCsvWriter() {
  if (file_ != nullptr) std::fclose(file_);
}

void SampleCsvWriter::write(const engine::Sample& s, const std::string& body_id) {
  if (file_ == nullptr) return;
  const int n = std::fprintf(file_, "%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%s,%.17g,%.17g,%.17g,%u,%d,%d\n", s.t,
                             s.position[0], s.position[1], s.position[2], s.force[0], s.force[1], s.force[2],
                             s.body >= 0 ? body_id.c_str() : "", s.u, s.v, s.depth, s.buttons, s.overrun ? 1 : 0,
                             s.fault ? 1 : 0);
  if (n < 0) failed_ = true;
}

bool SampleCsvWriter::close() {
  if (file_ == nullptr) return false;
  const bool good = std::fflush(file_) == 0 && !failed_ && std::ferror(file_) == 0;
  const bool closed = std::fclose(file_) == 0;
  file_ = nullptr;
  return good && closed;
}

bool write_marks_csv(const std::string& path, const engine::Trajectory& marks) {
  std::FILE* f = std::fopen(path.c_str(), "wb");
  if (f == nullptr) return false;
  bool good = std::fputs("t,x,y,z\n", f) >= 0;
  for (std::size_t k = 0; k < marks.t.size(); ++k) {
    good = good && std::fprintf(f, "%.17g,%.17g,%.17g,%.17g\n", marks.t[k], marks.position[k].x(),
                                marks.position[k].y(), marks.position[k].z()) > 0;
  }
  return std::fclose(f) == 0 && good;
}

}  // namespace palpa::cli
