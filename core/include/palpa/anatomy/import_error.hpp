#pragma once
// Why an anatomy cannot become a case: one line naming the file and what is wrong with it
// (a field, a label, a place in millimetres). palpa-cli import prints it and exits 2.
#include <stdexcept>

namespace palpa::anatomy {

class ImportError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace palpa::anatomy
