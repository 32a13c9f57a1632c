#pragma once
// "Map labels…" in the Import anatomy dialog: one row per label present in a label volume
// (with its voxel count) where the instructor gives its class, a name and, for tissue, skin
// and lesion, its Young's modulus in kPa; read back as an in-memory label table (Pa).
#include <cstddef>
#include <map>

#include <QTableWidget>

#include "palpa/anatomy/label_table.hpp"
#include "palpa/anatomy/label_volume.hpp"

namespace palpa::ui {

/// How many voxels carry each label.
std::map<int, std::size_t> count_labels(const anatomy::LabelVolume& volume);

class LabelMapTable : public QTableWidget {
  Q_OBJECT
 public:
  enum Column { kLabel, kVoxels, kClass, kName, kModulus };
  explicit LabelMapTable(QWidget* parent = nullptr);

  /// One row per label, label 0 outside and every other one tissue to begin with.
  void set_labels(const std::map<int, std::size_t>& counts);
  /// The table the rows give (moduli in Pa), named "labels mapped by hand".
  anatomy::LabelTable table() const;
  /// The mapping in one line, for the case's provenance: "0 outside; 1 tissue "fat" 3.24 kPa; ...",
  /// at most `max_bytes` long (whole entries, then "; ..."): the case keeps 1024 characters.
  std::string describe(std::size_t max_bytes = 900) const;

 private:
  void add_row(int row, int label, std::size_t voxels);
  void class_changed(int row);
};

}  // namespace palpa::ui
