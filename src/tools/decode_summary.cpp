#include "decode_summary.hpp"

namespace sercon::tools {

void DecodeSummary::add(const TelegramRow& row) {
  if (row.error) {
    ++errors_;
    ++by_error_[static_cast<std::size_t>(*row.error)];
    return;
  }
  ++telegrams_;
  ++by_kind_[static_cast<std::size_t>(*row.kind)];
  if (row.phase) {
    if (!row.phase_valid()) ++invalid_phase_msts_;
    if (phases_.empty() || phases_.back() != *row.phase) phases_.push_back(*row.phase);
  }
}

}  // namespace sercon::tools
