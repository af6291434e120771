#pragma once

#include <cstddef>
#include <string>
#include <utility>
#include <vector>

namespace fesd {

/// The link pairs an SRDF exempts from collision checking, or the reason it could not be read.
struct SrdfDisabledCollisions {
  std::vector<std::pair<std::string, std::string>> pairs;  ///< (link1, link2) in file order
  std::string error;                                       ///< empty on success
};

/// Reads every `<disable_collisions link1="..." link2="..."/>` under the SRDF's `<robot>`.
/// Text longer than max_bytes is refused unread (the text comes from a request).
SrdfDisabledCollisions disabledCollisionsFromSrdf(const std::string& srdf_xml,
                                                  std::size_t max_bytes = 1 << 20);

}  // namespace fesd
