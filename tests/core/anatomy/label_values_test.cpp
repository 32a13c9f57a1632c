// Labels as segmentation tools write them: any integer, negative ones included, and a
// background 0 the table need not list. A body labelled as patient MRI models label it
// (lesion -4, skin -2, muscle -1 as the support, fat 1) imports exactly as the same body
// in the generic table's labels.
#include <gtest/gtest.h>

#include <string>

#include "analytic_bodies.hpp"
#include "palpa/anatomy/import.hpp"
#include "palpa/anatomy/import_error.hpp"
#include "palpa/anatomy/label_table.hpp"

namespace palpa::anatomy {
namespace {

// The generic table's labels (0 outside, 1 tissue, 2 skin, 3 support, 4 lesion) as a
// patient model numbers them.
LabelVolume as_patient_labels(LabelVolume v) {
  for (auto& l : v.labels) {
    l = l == 1 ? 1 : l == 2 ? -2 : l == 3 ? -1 : l == 4 ? -4 : 0;
  }
  return v;
}

LabelTable patient_table(bool list_zero) {
  const LabelTable generic = builtin_label_table("generic");
  std::string text = R"({"labels": {)";
  if (list_zero) text += R"("0": {"class": "outside"}, )";
  text += R"("1": {"class": "tissue", "modulus": )" + std::to_string(generic.find(1)->modulus) +
          R"(}, "-2": {"class": "skin", "modulus": )" + std::to_string(generic.find(2)->modulus) +
          R"(}, "-1": {"class": "support"}, "-4": {"class": "lesion", "name": "malignant", "modulus": )" +
          std::to_string(generic.find(4)->modulus) + "}}}";
  return parse_label_table(text, "patient.json");
}

TEST(LabelValues, NegativeLabelsImportAsTheSameBody) {
  const LabelVolume generic = testing::voxelize(testing::dome_on_plane(), 2e-3);
  const ImportResult want = import_label_volume(generic, builtin_label_table("generic"), {}, "generic.nii");
  const ImportResult got = import_label_volume(as_patient_labels(generic), patient_table(true), {}, "patient.nii");
  ASSERT_EQ(got.body.grid.rows, want.body.grid.rows);
  ASSERT_EQ(got.body.grid.cols, want.body.grid.cols);
  for (std::size_t k = 0; k < want.body.grid.modulus.size(); ++k) {
    EXPECT_DOUBLE_EQ(got.body.grid.modulus[k], want.body.grid.modulus[k]);
  }
  ASSERT_EQ(got.tumours.size(), 1u);
  ASSERT_EQ(want.tumours.size(), 1u);
  for (std::size_t a = 0; a < 3; ++a) EXPECT_DOUBLE_EQ(got.tumours[0].center[a], want.tumours[0].center[a]);
  ASSERT_FALSE(got.lesions.empty());
  EXPECT_EQ(got.lesions[0].label, -4);
  EXPECT_EQ(got.lesions[0].name, "malignant");
  EXPECT_TRUE(got.notes.empty());
}

TEST(LabelValues, AnUnlistedZeroIsOutsideAndSaidSo) {
  const LabelVolume v = as_patient_labels(testing::voxelize(testing::dome_on_plane(), 2e-3));
  const ImportResult listed = import_label_volume(v, patient_table(true), {}, "patient.nii");
  const ImportResult unlisted = import_label_volume(v, patient_table(false), {}, "patient.nii");
  EXPECT_EQ(unlisted.body.grid.modulus, listed.body.grid.modulus);
  ASSERT_EQ(unlisted.notes.size(), 1u);
  EXPECT_EQ(unlisted.notes[0], "label 0 is not in the table \"patient.json\": taken as outside (the background)");
  // Any other unlisted label is still refused, naming it.
  LabelVolume stray = v;
  stray.labels[stray.index(30, 30, 12)] = -7;
  try {
    (void)import_label_volume(stray, patient_table(false), {}, "patient.nii");
    ADD_FAILURE() << "accepted a label the table does not list";
  } catch (const ImportError& e) {
    EXPECT_NE(std::string(e.what()).find("label -7: 1 voxels"), std::string::npos) << e.what();
  }
}

std::string refusal(const std::string& labels) {
  try {
    std::string text = R"({"labels": {)";
    text.append(labels).append("}}");
    (void)parse_label_table(text, "t.json");
  } catch (const ImportError& e) {
    return e.what();
  }
  return "accepted";
}

TEST(LabelValues, TableKeysAreIntegersOfAnySignWithinASpan) {
  const auto table = parse_label_table(R"({"labels": {"-4": {"class": "lesion", "modulus": 9000},
                                                       "0": {"class": "outside"}, "12": {"class": "support"}}})",
                                       "t.json");
  EXPECT_EQ(table.find(-4)->kind, LabelClass::Lesion);
  EXPECT_EQ(table.find(12)->kind, LabelClass::Support);
  for (const char* key : {"+1", "-0", "01", "-01", "1.5", "", "-", "2147483648", "-2147483649", "1e3", " 1"}) {
    std::string entry = "\"";
    entry.append(key).append(R"(": {"class": "outside"})");
    const auto why = refusal(entry);
    EXPECT_NE(why.find("is not an integer (such as -4, 0 or 12)"), std::string::npos) << key << ": " << why;
  }
  // The classes are looked up in an array over the labels' span: at most 2^20 values.
  EXPECT_EQ(refusal(R"("-524288": {"class": "outside"}, "524287": {"class": "support"})"), "accepted");
  EXPECT_NE(refusal(R"("-524288": {"class": "outside"}, "524288": {"class": "support"})").find(
                "labels from -524288 to 524288: they may span at most 1048576 values"),
            std::string::npos);
}

}  // namespace
}  // namespace palpa::anatomy
