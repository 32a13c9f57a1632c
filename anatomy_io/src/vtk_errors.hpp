#pragma once
// VTK's error reports turned into one-line refusals (internal): an observer on the reader or
// writer collects its ErrorEvent text, and VTK's own output window stays silent meanwhile.
#include <vtkCommand.h>
#include <vtkObject.h>

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

/// Silences VTK's output window (errors and warnings) while it lives; restores it after.
class QuietVtk {
 public:
  QuietVtk() : previous_(vtkObject::GetGlobalWarningDisplay()) { vtkObject::GlobalWarningDisplayOff(); }
  ~QuietVtk() { vtkObject::SetGlobalWarningDisplay(previous_); }
  QuietVtk(const QuietVtk&) = delete;
  QuietVtk& operator=(const QuietVtk&) = delete;

 private:
  int previous_;
};

}  // namespace palpa::anatomy_io::detail
