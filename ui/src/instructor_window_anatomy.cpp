// File > Import anatomy… (and Case > Import anatomy…): the dialog (ui/src/import_anatomy_dialog.hpp) imports and
// previews; "Use this case" makes the imported case the draft, provenance and all.
#include <QFileInfo>

#include "import_anatomy_dialog.hpp"
#include "palpa/ui/instructor_window.hpp"
#include "palpa/ui/trainee_window.hpp"

namespace palpa::ui {

void InstructorWindow::import_anatomy_dialog() {
  if (!confirm_discard()) return;
  auto* dialog = new ImportAnatomyDialog(this);
  dialog->setAttribute(Qt::WA_DeleteOnClose);
  connect(dialog, &QDialog::accepted, this, [this, dialog] {
    if (const auto* imported = dialog->imported()) {
      use_imported_case(imported->file);
    }
  });
  dialog->open();  // window-modal; the draft changes only on "Use this case"
}

void InstructorWindow::use_imported_case(const io::CaseFile& file) {
  commit_pending();
  const nlohmann::json& provenance = file.document.value("provenance", nlohmann::json::object());
  const std::string name = provenance.value("source", std::string("anatomy"));
  const std::string source = "imported " + name;
  // The document keeps what the import wrote besides the bodies and tumours
  // ("provenance", "exam_region"); saving writes them back (io::to_json).
  draft_ = author::CaseDraft::from_document(io::to_json(file), source);
  drawn_bodies_ = nlohmann::json();
  refresh();
  frame_camera();
  const auto problems = draft_.validate();
  const QString shown = QString::fromStdString(name);
  set_message(problems.empty() ? tr("Imported %1: check it, then Save As to keep it.").arg(shown)
                               : tr("Imported %1: %2 problem(s), listed below.").arg(shown).arg(problems.size()));
}

}  // namespace palpa::ui
