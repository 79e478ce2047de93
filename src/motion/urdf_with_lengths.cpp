#include "motion/urdf_with_lengths.hpp"

#include <fmt/format.h>
#include <tinyxml.h>

#include "motion/urdf_model.hpp"

namespace armctl::motion {

namespace {

Error config_error(std::string message) { return Error{ErrorKind::invalid_config, std::move(message)}; }

const OriginLength* length_of(std::span<const OriginLength> lengths, const char* joint) {
  if (joint == nullptr) return nullptr;
  for (const OriginLength& l : lengths)
    if (l.joint == joint) return &l;
  return nullptr;
}

}  // namespace

Result<std::string> urdf_with_origin_lengths(std::string_view urdf_xml, std::span<const OriginLength> lengths) {
  if (lengths.empty()) return std::string(urdf_xml);
  // urdfdom first: it guards the text (UTF-8, well-formed) and apply_origin_lengths checks
  // each length and computes the new offset exactly as the kinematics gets it.
  auto parsed = parse_urdf_model(std::string(urdf_xml));
  if (!parsed) return parsed.error();
  if (Status s = apply_origin_lengths(**parsed, lengths); !s) return s.error();

  // The same TinyXML urdfdom reads with, to change one attribute per joint and print the rest
  // back as it was.
  TiXmlDocument doc;
  doc.Parse(std::string(urdf_xml).c_str(), nullptr, TIXML_ENCODING_UTF8);
  TiXmlElement* robot = doc.RootElement();
  if (doc.Error() || robot == nullptr) return config_error(fmt::format("URDF: {}", doc.ErrorDesc()));
  std::size_t written = 0;
  for (TiXmlElement* joint = robot->FirstChildElement("joint"); joint != nullptr;
       joint = joint->NextSiblingElement("joint")) {
    const OriginLength* l = length_of(lengths, joint->Attribute("name"));
    if (l == nullptr) continue;
    // apply_origin_lengths refused a joint without an offset, so the <origin> is there.
    TiXmlElement* origin = joint->FirstChildElement("origin");
    if (origin == nullptr) return config_error(fmt::format("URDF joint '{}' has no <origin>", l->joint));
    const urdf::Vector3& p = (*parsed)->joints_.at(l->joint)->parent_to_joint_origin_transform.position;
    origin->SetAttribute("xyz", fmt::format("{:.10g} {:.10g} {:.10g}", p.x, p.y, p.z));
    ++written;
  }
  // urdfdom would have refused a joint name given twice in the file; one written per length.
  if (written != lengths.size())
    return config_error(fmt::format("URDF: {} of {} link lengths found a <joint> at the top level", written,
                                    lengths.size()));
  TiXmlPrinter printer;
  printer.SetIndent("  ");
  doc.Accept(&printer);
  return std::string(printer.CStr());
}

}  // namespace armctl::motion
