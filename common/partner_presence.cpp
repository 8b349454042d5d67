#include "partner_presence.hpp"

namespace nerv {

bool PartnerPresence::arrived(int64_t seq) {
  missed_in_a_row_ = 0;
  start_unanswered_ = false;
  return sent_alone_.erase(seq) == 0;
}

bool PartnerPresence::goesAlone(int64_t seq) {
  if (!absent()) {
    sent_alone_.erase(seq);
    return false;
  }
  wentAlone(seq);
  return true;
}

void PartnerPresence::wentAlone(int64_t seq) {
  sent_alone_.insert(seq);
  while (sent_alone_.size() > kMemory) sent_alone_.erase(sent_alone_.begin());
}

}  // namespace nerv
