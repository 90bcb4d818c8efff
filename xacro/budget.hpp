// The expansion budget: how much one expansion may build (strings, lists, XML nodes, macro calls, document text),
// set far above any real robot so that a runaway or hostile file is refused with file:line and the budget it
// crossed, before it exhausts memory. The budget holds for the thread that runs expand_file.
#pragma once

#include <cstddef>

namespace lcm_control::xacro {

struct Budget {
  // Defaults: at least 400 times what the largest ROS 2 robot of the test suite builds (the UR5e: strings of 270
  // bytes, lists of 60 items, 1,412 evaluation steps, 2,490 nodes, 50 macro calls, 4 includes, 91 KB of document
  // text), and small enough that reaching any of them costs < 500 MB and < 2 s.
  std::size_t string_bytes = 16u << 20;    // one string value
  std::size_t list_items = 1u << 18;       // one list, tuple or dict
  std::size_t operations = 4u << 20;       // expression evaluation steps, all of them (a loop that builds nothing)
  std::size_t nodes = 1u << 20;            // XML nodes made: parsed, cloned by macro calls, created
  std::size_t macro_calls = 100000;        // macro calls, all of them
  std::size_t includes = 10000;            // files included (each read and parsed again), all of them
  std::size_t document_bytes = 64u << 20;  // text put into the document (parsed, cloned, substituted); its output

  // Every budget times factor (> 0); the programs take the factor from LCM_CONTROL_XACRO_BUDGET (xacro: --budget).
  Budget scaled(double factor) const;
};

// What one expansion used, against its budget (xacro --stats prints it).
struct BudgetUse {
  std::size_t largest_string = 0, largest_list = 0, operations = 0, nodes = 0, macro_calls = 0, includes = 0,
              document_bytes = 0;
};

// Puts a budget in force on this thread for its lifetime (expand_file holds one).
class BudgetScope {
 public:
  explicit BudgetScope(const Budget& budget);
  ~BudgetScope();
  BudgetScope(const BudgetScope&) = delete;
  BudgetScope& operator=(const BudgetScope&) = delete;
  const BudgetUse& use() const { return use_; }

 private:
  friend struct BudgetCounters;
  Budget budget_;
  BudgetUse use_;
  BudgetScope* previous_;
};

// Each counts toward the budget in force (none: unlimited) and throws ProcessError naming the budget when it is
// crossed. A caller checks a size before it allocates it.
void check_string(std::size_t bytes);
void check_list(std::size_t items);
void count_operation();
void count_nodes(std::size_t n);
void count_macro_call();
void count_include();
void count_document_bytes(std::size_t bytes);
void check_document(std::size_t bytes);  // the document as written out, indentation included

// Whether the calling thread's stack has less than kStackReserve left below the caller's frame: the recursive
// readers and evaluators refuse to go deeper then, whatever their level counts say, so that a build whose frames
// are larger (unoptimised, sanitised) or a thread with a small stack stops with a message, never a crash.
inline constexpr std::size_t kStackReserve = 256u << 10;
bool stack_nearly_full();

}  // namespace lcm_control::xacro
