// The one exception type of the baker: its message is a complete one-line diagnosis for the user.
#pragma once

#include <stdexcept>
#include <string>

namespace ibl {

class Error : public std::runtime_error {
  public:
    using std::runtime_error::runtime_error;
};

} // namespace ibl
