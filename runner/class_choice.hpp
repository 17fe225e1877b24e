#pragma once
// Which classes a run keeps: `detector.classes` names them by the model's own labels (COCO's for
// the bundled model; a labels file named by the model's description for another,
// detector/model_description.hpp) or by column number, so they are resolved once the model is
// known, not when the setting is read: "apple" is column 53 of COCO's table and column 1 of a
// fruit model's.
#include <memory>
#include <vector>

#include "detector/label_table.hpp"
#include "runner/run_config.hpp"

namespace rtmot::runner {

/// The labels of the run's model (read from its description's labels file), COCO's table for a
/// model without one and for the replay detector. Throws InputError (ExitCode::bad_model) for a
/// description or labels file that does not read.
std::shared_ptr<const detector::LabelTable> run_labels(const RunConfig& config);

/// detector.classes as column ids of `labels` (empty: every class). Throws InputError
/// (ExitCode::usage) naming the configuration file, the line the setting was read from and the
/// field, with the labels' source, for a name the labels do not have or a column outside them.
std::vector<int> resolve_classes(const RunConfig& config, const detector::LabelTable& labels);

/// resolve_classes() against run_labels(): the check `rtmot run` makes before opening anything.
void check_classes(const RunConfig& config);

}  // namespace rtmot::runner
