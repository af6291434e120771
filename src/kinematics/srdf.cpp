#include "fesd_trajopt/kinematics/srdf.h"

#include <tinyxml2.h>

namespace fesd {

SrdfDisabledCollisions disabledCollisionsFromSrdf(const std::string& srdf_xml,
                                                  std::size_t max_bytes) {
  SrdfDisabledCollisions result;
  if (srdf_xml.size() > max_bytes) {
    result.error = "the SRDF has " + std::to_string(srdf_xml.size()) + " bytes, more than " +
                   std::to_string(max_bytes);
    return result;
  }
  tinyxml2::XMLDocument document;
  if (document.Parse(srdf_xml.c_str(), srdf_xml.size()) != tinyxml2::XML_SUCCESS) {
    result.error = std::string("malformed SRDF: ") + document.ErrorStr();
    return result;
  }
  const tinyxml2::XMLElement* robot = document.FirstChildElement("robot");
  if (!robot) {
    result.error = "malformed SRDF: no <robot> element";
    return result;
  }
  for (const tinyxml2::XMLElement* entry = robot->FirstChildElement("disable_collisions"); entry;
       entry = entry->NextSiblingElement("disable_collisions")) {
    const char* link1 = entry->Attribute("link1");
    const char* link2 = entry->Attribute("link2");
    if (!link1 || !link2) {
      result.error = "malformed SRDF: a <disable_collisions> on line " +
                     std::to_string(entry->GetLineNum()) + " lacks link1 or link2";
      result.pairs.clear();
      return result;
    }
    result.pairs.emplace_back(link1, link2);
  }
  return result;
}

}  // namespace fesd
