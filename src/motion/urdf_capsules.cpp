#include "motion/urdf_capsules.hpp"

#include <cmath>

#include <fmt/format.h>
#include <tinyxml.h>

#include "core/printable.hpp"

namespace armctl::motion {

namespace {

Error config_error(std::string message) { return Error{ErrorKind::invalid_config, std::move(message)}; }

// The attribute as a length above 0 (m), or an error naming where it is.
Result<double> size_of(const TiXmlElement& capsule, const char* attribute, const std::string& what) {
  double v = 0;
  if (capsule.QueryDoubleAttribute(attribute, &v) != TIXML_SUCCESS || !std::isfinite(v) || !(v > 0))
    return config_error(fmt::format("URDF {}: <capsule {}=\"{}\">: wants a length above 0 (m)", what, attribute,
                                    capsule.Attribute(attribute) ? printable(capsule.Attribute(attribute)) : "(missing)"));
  return v;
}

}  // namespace

Result<UrdfWithoutCapsules> without_capsules(const std::string& xml) {
  UrdfWithoutCapsules out;
  if (xml.find("<capsule") == std::string::npos) {
    out.xml = xml;
    return out;
  }
  TiXmlDocument doc;
  doc.Parse(xml.c_str(), nullptr, TIXML_ENCODING_UTF8);
  TiXmlElement* robot = doc.RootElement();
  // Not XML: urdfdom says why, in the words its users know.
  if (doc.Error() || robot == nullptr) {
    out.xml = xml;
    return out;
  }
  for (TiXmlElement* link = robot->FirstChildElement("link"); link; link = link->NextSiblingElement("link")) {
    const std::string name = link->Attribute("name") ? link->Attribute("name") : "";
    for (const char* kind : {"collision", "visual"}) {
      std::size_t n = 0;
      for (TiXmlElement* e = link->FirstChildElement(kind); e; e = e->NextSiblingElement(kind), ++n) {
        TiXmlElement* geometry = e->FirstChildElement("geometry");
        TiXmlElement* capsule = geometry ? geometry->FirstChildElement("capsule") : nullptr;
        if (capsule == nullptr) continue;
        const std::string what = fmt::format("link '{}' <{}> {}", printable(name), kind, n + 1);
        auto radius = size_of(*capsule, "radius", what);
        if (!radius) return radius.error();
        auto length = size_of(*capsule, "length", what);
        if (!length) return length.error();
        capsule->SetValue("cylinder");
        if (std::string(kind) == "collision") out.capsules.push_back({name, n, *radius, *length});
      }
    }
  }
  TiXmlPrinter printer;
  doc.Accept(&printer);
  out.xml = printer.CStr();
  return out;
}

}  // namespace armctl::motion
