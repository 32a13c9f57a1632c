// The built-in label tables (docs/anatomy-import.md, "Label tables", with the sources of
// every modulus).
#include <fmt/format.h>

#include "palpa/anatomy/import_error.hpp"
#include "palpa/anatomy/label_table.hpp"
#include "palpa/mat/tissue_materials.hpp"

namespace palpa::anatomy {

namespace {

// Dermis in vivo under indentation with a two-layer model (Pailler-Mattei, Bec and
// Zahouani, Med. Eng. Phys. 30 (2008) 599-606).
constexpr double kSkin = 35e3;
// Fibrous tissue at 5 % pre-compression (Krouskop et al., Ultrasonic Imaging 20 (1998)):
// Cooper's ligaments are fibrous bands.
constexpr double kFibrous = 96e3;

LabelEntry material(const char* key, LabelClass kind, const char* name) {
  const mat::TissueMaterial* m = mat::find_tissue_material(key);
  return {kind, name, m->modulus, m->stiffening};
}

LabelTable victre() {
  // Labels of the VICTRE breast phantom generator (breastPhantom, DIDSR); mass and
  // calcification are the labels VICTRE's lesion tools insert.
  LabelTable t;
  t.name = "victre";
  t.labels[0] = {LabelClass::Outside, "air", 0.0, 0.0};
  t.labels[1] = material("fat", LabelClass::Tissue, "fat");
  t.labels[2] = {LabelClass::Skin, "skin", kSkin, 0.0};
  t.labels[29] = material("fibroglandular", LabelClass::Tissue, "glandular");
  t.labels[33] = {LabelClass::Skin, "nipple", kSkin, 0.0};
  t.labels[40] = {LabelClass::Support, "muscle", 0.0, 0.0};
  t.labels[88] = {LabelClass::Tissue, "ligament", kFibrous, 0.0};
  t.labels[95] = material("fibroglandular", LabelClass::Tissue, "TDLU");
  t.labels[125] = material("fibroglandular", LabelClass::Tissue, "duct");
  t.labels[150] = material("fat", LabelClass::Tissue, "artery");
  t.labels[225] = material("fat", LabelClass::Tissue, "vein");
  t.labels[200] = material("carcinoma", LabelClass::Lesion, "mass");
  t.labels[250] = material("carcinoma-high-grade", LabelClass::Lesion, "calcification");
  return t;
}

LabelTable generic() {
  LabelTable t;
  t.name = "generic";
  t.labels[0] = {LabelClass::Outside, "outside", 0.0, 0.0};
  t.labels[1] = material("fibroglandular", LabelClass::Tissue, "tissue");
  t.labels[2] = {LabelClass::Skin, "skin", kSkin, 0.0};
  t.labels[3] = {LabelClass::Support, "support", 0.0, 0.0};
  t.labels[4] = material("carcinoma", LabelClass::Lesion, "lesion");
  return t;
}

}  // namespace

LabelTable builtin_label_table(std::string_view name) {
  if (name == "victre") return victre();
  if (name == "generic") return generic();
  throw ImportError(fmt::format("--labels: \"{}\" is neither a built-in table (victre, generic) nor a .json file",
                                std::string(name.substr(0, 64))));
}

std::vector<std::string> builtin_label_table_names() { return {"victre", "generic"}; }

}  // namespace palpa::anatomy
