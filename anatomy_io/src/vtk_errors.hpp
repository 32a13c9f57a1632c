#pragma once
// VTK's error reports turned into one-line refusals (internal): an observer on the reader or
// writer collects its ErrorEvent text, and VTK's own output window stays silent meanwhile.
#include <vtkCommand.h>
#include <vtkObject.h>
#include <vtkLogger.h>
#include <vtkOutputWindow.h>

#include <string>

namespace palpa::anatomy_io::detail {

class ErrorCatcher : public vtkCommand {
 public:
  static ErrorCatcher* New() { return new ErrorCatcher; }
  void Execute(vtkObject* caller, unsigned long event, void* data) override;
  bool failed() const { return failed_; }
  /// The last message, without VTK's source-file prefix, on one line.
  const std::string& message() const { return message_; }

 private:
  bool failed_ = false;
  std::string message_;
};

/// While it lives, VTK's output window is one that shows nothing and keeps the last error
/// text (errors of objects without an observer, such as a reader's XML parser); the previous
/// window is restored after; so is VTK's log on stderr (VTK 9 logs errors there too), whose
/// level is put back to the cutoff it had. VTK's output window is process-wide: reads on several threads at
/// once would share it (the import reads on one).
class QuietVtk {
 public:
  QuietVtk();
  ~QuietVtk();
  QuietVtk(const QuietVtk&) = delete;
  QuietVtk& operator=(const QuietVtk&) = delete;
  /// The last error VTK sent to the output window, on one line; empty when none.
  std::string last_error() const;

 private:
  vtkOutputWindow* previous_;
  vtkOutputWindow* window_;
  vtkLogger::Verbosity log_level_;
};

}  // namespace palpa::anatomy_io::detail
