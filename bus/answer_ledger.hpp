// A service's answers over a lossy bus: the client sends a request again under
// the same request_id until an answer comes, and the service answers a request
// it has already answered with that same answer (or stays silent while it is
// still at work on it), so that a lost request or answer costs one resend and
// nothing is done twice. Answer: an lcm message with int64_t request_id.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <deque>

namespace lcm_control {

template <class Answer>
class AnswerLedger {
 public:
  enum class Seen { New, Working, Answered };

  explicit AnswerLedger(size_t remembered = 64) : remembered_(remembered) {}

  // What became of request_id so far; *answer points at the answer given when Answered. Ids <= 0 are always New
  // (malformed requests are answered as -1).
  Seen seen(int64_t request_id, const Answer** answer = nullptr) const {
    if (request_id <= 0) return Seen::New;
    for (const Answer& a : answers_)
      if (a.request_id == request_id) {
        if (answer) *answer = &a;
        return Seen::Answered;
      }
    return std::find(working_.begin(), working_.end(), request_id) != working_.end() ? Seen::Working : Seen::New;
  }

  // Taken on, to be answered later.
  void working(int64_t request_id) {
    if (request_id <= 0 || seen(request_id) != Seen::New) return;
    working_.push_back(request_id);
    if (working_.size() > remembered_) working_.pop_front();
  }

  // The first answer to a request is the one repeated; later ones (a command source's end) are not remembered.
  void answered(const Answer& a) {
    if (a.request_id <= 0) return;
    working_.erase(std::remove(working_.begin(), working_.end(), a.request_id), working_.end());
    if (seen(a.request_id) == Seen::Answered) return;
    answers_.push_back(a);
    if (answers_.size() > remembered_) answers_.pop_front();
  }

 private:
  size_t remembered_;
  std::deque<Answer> answers_;
  std::deque<int64_t> working_;
};

}  // namespace lcm_control
