// A situation the model refuses to simulate, though nothing in it is a wrong argument or a
// model fault: the message says what and why (a ring where every node repeats, whose
// telegrams would circle it for ever). The C API returns SERCON_ERR_UNSUPPORTED for it.
#pragma once

#include <stdexcept>
#include <string>

namespace sercon::sim {

class ModelLimit : public std::runtime_error {
 public:
  explicit ModelLimit(const std::string& what) : std::runtime_error(what) {}
};

}  // namespace sercon::sim
