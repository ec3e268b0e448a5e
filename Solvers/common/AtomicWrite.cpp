#include "common/AtomicWrite.h"

#include "common/Error.h"

#include <cstdio>
#include <fstream>
#include <stdexcept>

namespace craterkit {

void writeFileAtomically(const std::string& path, const std::string& what,
                         const std::function<void(std::ostream&)>& write) {
  const std::string part = path + ".part";
  {
    std::ofstream out(part, std::ios::binary | std::ios::trunc);
    if (!out)
      throw InputError(part + ": cannot write " + what);
    write(out);
    if (!out.flush())
      throw std::runtime_error(part + ": writing " + what + " failed (disk full?)");
  }
  if (std::rename(part.c_str(), path.c_str()) != 0)
    throw std::runtime_error(path + ": cannot move " + what + " into place");
}

} // namespace craterkit
