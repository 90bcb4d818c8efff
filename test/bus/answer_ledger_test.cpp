// common/answer_ledger: a repeated request id gets the first answer, is silent while in work, and old ids are
// forgotten.
#include "bus/answer_ledger.hpp"

#include <gtest/gtest.h>

#include <string>

using lcm_control::AnswerLedger;

namespace {
struct Answer {
  int64_t request_id = 0;
  std::string message;
};
using Seen = AnswerLedger<Answer>::Seen;
}  // namespace

TEST(AnswerLedger, NewThenWorkingThenTheFirstAnswerForEver) {
  AnswerLedger<Answer> ledger;
  EXPECT_EQ(ledger.seen(5), Seen::New);
  ledger.working(5);
  EXPECT_EQ(ledger.seen(5), Seen::Working);
  ledger.answered({5, "started"});
  const Answer* a = nullptr;
  ASSERT_EQ(ledger.seen(5, &a), Seen::Answered);
  EXPECT_EQ(a->message, "started");
  ledger.answered({5, "ended"});  // a later answer under the same id does not replace the first
  ASSERT_EQ(ledger.seen(5, &a), Seen::Answered);
  EXPECT_EQ(a->message, "started");
}

TEST(AnswerLedger, IdsUpToZeroAreNeverRememberedAndOldAnswersAreForgotten) {
  AnswerLedger<Answer> ledger(2);
  ledger.answered({-1, "malformed"});
  ledger.working(0);
  EXPECT_EQ(ledger.seen(-1), Seen::New);
  EXPECT_EQ(ledger.seen(0), Seen::New);
  ledger.answered({1, "a"});
  ledger.answered({2, "b"});
  ledger.answered({3, "c"});
  EXPECT_EQ(ledger.seen(1), Seen::New);
  EXPECT_EQ(ledger.seen(2), Seen::Answered);
  EXPECT_EQ(ledger.seen(3), Seen::Answered);
}
