#include "motion/urdf_for_viewers.hpp"

#include <string>
#include <utility>
#include <vector>

#include <fmt/format.h>
#include <tinyxml.h>

#include "core/printable.hpp"
#include "motion/urdf_model.hpp"

namespace armctl::motion {

namespace {

Error config_error(std::string message) { return Error{ErrorKind::invalid_config, std::move(message)}; }

std::string xyz_text(double x, double y, double z) { return fmt::format("{:.10g} {:.10g} {:.10g}", x, y, z); }

const OriginLength* length_of(std::span<const OriginLength> lengths, const char* joint) {
  if (joint == nullptr) return nullptr;
  for (const OriginLength& l : lengths)
    if (l.joint == joint) return &l;
  return nullptr;
}

// The <collision> or <visual> element `shape` (its geometry a <capsule>) made the capsule's
// cylinder, and a copy of it with a sphere put after it for each end. `origin` and `size` are
// the element's pose and its capsule as urdfdom read them (a cylinder of its size:
// motion/urdf_capsules.hpp, which checked the sizes).
void expand_capsule(TiXmlElement& shape, const urdf::Pose& origin, const urdf::Cylinder& size) {
  const double radius = size.radius, length = size.length;
  shape.FirstChildElement("geometry")->FirstChildElement("capsule")->SetValue("cylinder");
  TiXmlNode* after = &shape;
  for (const double end : {-0.5 * length, 0.5 * length}) {
    TiXmlElement sphere_shape(shape);
    TiXmlElement* geometry = sphere_shape.FirstChildElement("geometry");
    geometry->Clear();
    TiXmlElement sphere("sphere");
    sphere.SetAttribute("radius", fmt::format("{:.10g}", radius));
    geometry->InsertEndChild(sphere);
    // The end's centre: the element's origin moved along its own z.
    const urdf::Vector3 along = origin.rotation * urdf::Vector3(0, 0, end);
    TiXmlElement* o = sphere_shape.FirstChildElement("origin");
    if (o == nullptr) o = sphere_shape.InsertEndChild(TiXmlElement("origin"))->ToElement();
    o->SetAttribute("xyz", xyz_text(origin.position.x + along.x, origin.position.y + along.y, origin.position.z + along.z));
    after = shape.Parent()->InsertAfterChild(after, sphere_shape);
  }
}

}  // namespace

Result<std::string> urdf_for_viewers(std::string_view urdf_xml, std::span<const OriginLength> lengths) {
  const std::string text(urdf_xml);
  const bool capsules = text.find("<capsule") != std::string::npos;
  if (lengths.empty() && !capsules) return text;
  // urdfdom first: it guards the text (UTF-8, well-formed, capsule sizes) and
  // apply_origin_lengths checks each length and computes the new offset exactly as the
  // kinematics gets it.
  auto parsed = parse_urdf_model(text);
  if (!parsed) return parsed.error();
  if (Status s = apply_origin_lengths(**parsed, lengths); !s) return s.error();

  // The same TinyXML urdfdom reads with, to change what is needed and print the rest back.
  TiXmlDocument doc;
  doc.Parse(text.c_str(), nullptr, TIXML_ENCODING_UTF8);
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
    origin->SetAttribute("xyz", xyz_text(p.x, p.y, p.z));
    ++written;
  }
  // urdfdom would have refused a joint name given twice in the file; one written per length.
  if (written != lengths.size())
    return config_error(fmt::format("URDF: {} of {} link lengths found a <joint> at the top level", written,
                                    lengths.size()));
  for (TiXmlElement* link = robot->FirstChildElement("link"); capsules && link; link = link->NextSiblingElement("link")) {
    const urdf::LinkConstSharedPtr parsed_link = (*parsed)->getLink(link->Attribute("name") ? link->Attribute("name") : "");
    if (!parsed_link) continue;
    // Collect first: each expansion adds siblings. urdfdom's arrays are in document order.
    for (const char* kind : {"collision", "visual"}) {
      struct Found {
        TiXmlElement* element;
        urdf::Pose origin;
        urdf::GeometrySharedPtr geometry;
      };
      std::vector<Found> found;
      std::size_t n = 0;
      for (TiXmlElement* e = link->FirstChildElement(kind); e; e = e->NextSiblingElement(kind), ++n) {
        const TiXmlElement* geometry = e->FirstChildElement("geometry");
        if (!geometry || !geometry->FirstChildElement("capsule")) continue;
        const bool collision = std::string(kind) == "collision";
        const std::size_t count = collision ? parsed_link->collision_array.size() : parsed_link->visual_array.size();
        Found f{e, {}, nullptr};
        if (n < count) {
          f.origin = collision ? parsed_link->collision_array[n]->origin : parsed_link->visual_array[n]->origin;
          f.geometry = collision ? parsed_link->collision_array[n]->geometry : parsed_link->visual_array[n]->geometry;
        }
        if (!f.geometry || f.geometry->type != urdf::Geometry::CYLINDER)
          return config_error(fmt::format("URDF link '{}': its <{}> elements are not as read",
                                          printable(link->Attribute("name") ? link->Attribute("name") : ""), kind));
        found.push_back(std::move(f));
      }
      for (const Found& f : found)
        expand_capsule(*f.element, f.origin, static_cast<const urdf::Cylinder&>(*f.geometry));
    }
  }
  TiXmlPrinter printer;
  printer.SetIndent("  ");
  doc.Accept(&printer);
  return std::string(printer.CStr());
}

}  // namespace armctl::motion
