#include "runner/yaml_document.hpp"

#include <yaml-cpp/eventhandler.h>

#include <sstream>

#include "common/input_error.hpp"

namespace rtmot::runner {
namespace {

// Notes where the newest document's content starts (its first node: what a reader sees as the
// document) and ignores the rest: counting documents needs no tree.
class DocumentStarts final : public YAML::EventHandler {
 public:
  YAML::Mark content_start() const { return content_start_; }

  void OnDocumentStart(const YAML::Mark& mark) override {
    content_start_ = mark;
    content_seen_ = false;
  }
  void OnDocumentEnd() override {}
  void OnNull(const YAML::Mark& mark, YAML::anchor_t) override { note(mark); }
  void OnAlias(const YAML::Mark& mark, YAML::anchor_t) override { note(mark); }
  void OnScalar(const YAML::Mark& mark, const std::string&, YAML::anchor_t,
                const std::string&) override {
    note(mark);
  }
  void OnSequenceStart(const YAML::Mark& mark, const std::string&, YAML::anchor_t,
                       YAML::EmitterStyle::value) override {
    note(mark);
  }
  void OnSequenceEnd() override {}
  void OnMapStart(const YAML::Mark& mark, const std::string&, YAML::anchor_t,
                  YAML::EmitterStyle::value) override {
    note(mark);
  }
  void OnMapEnd() override {}

 private:
  void note(const YAML::Mark& mark) {
    if (content_seen_) return;
    content_start_ = mark;
    content_seen_ = true;
  }

  YAML::Mark content_start_;
  bool content_seen_{false};
};

}  // namespace

YAML::Node load_one_document(const std::string& yaml_text, const std::string& file_name,
                             const std::string& what) {
  YAML::Node first;
  try {
    first = YAML::Load(yaml_text);
    // At most two documents are asked for. yaml-cpp 0.7's LoadAll() never ends on a stray ',' at
    // the top level (an endless run of empty documents, memory growing: found by fuzz_run_config),
    // so the documents are counted with a bounded parse instead of loading them all.
    std::istringstream stream(yaml_text);
    YAML::Parser parser(stream);
    DocumentStarts starts;
    if (parser.HandleNextDocument(starts) && parser.HandleNextDocument(starts) && !first.IsNull()) {
      throw InputError(file_name, starts.content_start().line + 1, "",
                       "a second YAML document: " + what +
                           " is one document (remove the '---' and what follows, or merge it "
                           "into the first)");
    }
  } catch (const YAML::ParserException& error) {
    throw InputError(file_name, error.mark.line + 1, "", "not valid YAML: " + error.msg);
  }
  if (first.IsNull())
    throw InputError(file_name, 0, "", "the file is empty: " + what + " is expected");
  return first;
}

}  // namespace rtmot::runner
