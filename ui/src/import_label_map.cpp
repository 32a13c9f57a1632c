#include "import_label_map.hpp"

#include <array>
#include <vector>

#include <fmt/format.h>
#include <QComboBox>
#include <QDoubleSpinBox>
#include <QHeaderView>

#include "spin_box.hpp"

namespace palpa::ui {
namespace {

using anatomy::LabelClass;

// In the order the class boxes list them.
constexpr std::array<LabelClass, 5> kClasses = {LabelClass::Tissue, LabelClass::Skin, LabelClass::Support,
                                                LabelClass::Lesion, LabelClass::Outside};

// A class's modulus and stiffening to begin with: the built-in generic table's.
anatomy::LabelEntry class_default(LabelClass kind) {
  static const anatomy::LabelTable generic = anatomy::builtin_label_table("generic");
  for (const auto& [label, entry] : generic.labels) {
    if (entry.kind == kind) return entry;
  }
  return {kind, "", 0.0, 0.0};
}

}  // namespace

std::map<int, std::size_t> count_labels(const anatomy::LabelVolume& volume) {
  const auto counts = anatomy::label_counts(volume);
  return {counts.begin(), counts.end()};
}

LabelMapTable::LabelMapTable(QWidget* parent) : QTableWidget(0, 5, parent) {
  setHorizontalHeaderLabels({tr("Label"), tr("Voxels"), tr("Class"), tr("Name"), tr("Modulus")});
  horizontalHeader()->setSectionResizeMode(kName, QHeaderView::Stretch);
  verticalHeader()->setVisible(false);
  setSelectionMode(QAbstractItemView::NoSelection);
}

void LabelMapTable::set_labels(const std::map<int, std::size_t>& counts) {
  setRowCount(0);
  setRowCount(static_cast<int>(counts.size()));
  int row = 0;
  for (const auto& [label, voxels] : counts) add_row(row++, label, voxels);
  resizeColumnsToContents();
}

void LabelMapTable::add_row(int row, int label, std::size_t voxels) {
  for (const auto& [column, text] : {std::pair{kLabel, QString::number(label)}, {kVoxels, QString::number(voxels)}}) {
    auto* item = new QTableWidgetItem(text);
    item->setFlags(Qt::ItemIsEnabled);
    item->setTextAlignment(Qt::AlignRight | Qt::AlignVCenter);
    setItem(row, column, item);
  }
  auto* kind = new QComboBox(this);
  for (LabelClass c : kClasses) kind->addItem(anatomy::to_string(c), static_cast<int>(c));
  kind->setCurrentIndex(label == 0 ? 4 : 0);
  setCellWidget(row, kClass, kind);
  setItem(row, kName, new QTableWidgetItem(label == 0 ? tr("outside") : tr("label %1").arg(label)));
  auto* modulus = spin(this, 0.01, 1e6, 0.5, 2, tr(" kPa"));
  setCellWidget(row, kModulus, modulus);
  class_changed(row);
  connect(kind, qOverload<int>(&QComboBox::currentIndexChanged), this, [this, kind] {
    for (int r = 0; r < rowCount(); ++r) {
      if (cellWidget(r, kClass) == kind) class_changed(r);
    }
  });
}

void LabelMapTable::class_changed(int row) {
  const auto kind = static_cast<LabelClass>(static_cast<QComboBox*>(cellWidget(row, kClass))->currentData().toInt());
  auto* modulus = static_cast<QDoubleSpinBox*>(cellWidget(row, kModulus));
  const bool soft = anatomy::LabelTable::soft(kind);
  modulus->setEnabled(soft);
  modulus->setValue(soft ? class_default(kind).modulus / 1e3 : modulus->minimum());
  modulus->setSpecialValueText(soft ? QString() : QString("-"));
}

anatomy::LabelTable LabelMapTable::table() const {
  anatomy::LabelTable out;
  out.name = "labels mapped by hand";
  for (int row = 0; row < rowCount(); ++row) {
    const int label = item(row, kLabel)->text().toInt();
    anatomy::LabelEntry entry;
    entry.kind = static_cast<LabelClass>(static_cast<QComboBox*>(cellWidget(row, kClass))->currentData().toInt());
    entry.name = item(row, kName)->text().trimmed().toStdString();
    if (anatomy::LabelTable::soft(entry.kind)) {
      entry.modulus = static_cast<QDoubleSpinBox*>(cellWidget(row, kModulus))->value() * 1e3;
      entry.stiffening = class_default(entry.kind).stiffening;
    }
    out.labels[label] = entry;
  }
  return out;
}

std::string LabelMapTable::describe(std::size_t max_bytes) const {
  std::string out;
  for (const auto& [label, e] : table().labels) {
    std::string entry = fmt::format("{} {}", label, anatomy::to_string(e.kind));
    if (anatomy::LabelTable::soft(e.kind)) entry += fmt::format(" \"{}\" {:g} kPa", e.name, e.modulus / 1e3);
    // Whole entries only, so that a name's UTF-8 is never cut.
    if (out.size() + entry.size() + 6 > max_bytes) return out + "; ...";
    out += (out.empty() ? "" : "; ") + entry;
  }
  return out;
}

}  // namespace palpa::ui
