#include "core/engines/recognition_engine.h"

namespace orbit {

RecognitionEngine::RecognitionEngine(std::string_view name, const EngineOptions& options)
    : name_(name), options_(options) {
  ValidateEngineOptions(options_);
}

RecognitionEngine::~RecognitionEngine() = default;

}  // namespace orbit
