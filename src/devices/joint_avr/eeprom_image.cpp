#include "devices/joint_avr/eeprom_image.hpp"

#include <string>

#include "core/error.hpp"

namespace armctl::joint_avr {
namespace {
constexpr std::uint8_t config_magic = 0x4A;
constexpr std::uint8_t tuning_magic = 0x54;
constexpr std::size_t tuning_size = 24;

void put_int32(std::vector<std::uint8_t>& out, std::size_t at, std::int32_t v) {
  const auto u = static_cast<std::uint32_t>(v);
  for (std::size_t i = 0; i < 4; ++i) out[at + i] = static_cast<std::uint8_t>(u >> (8 * i));
}
}  // namespace

std::vector<std::uint8_t> raw_eeprom_image(std::uint8_t magic, std::uint8_t joint,
                                           std::uint8_t baud_code, std::uint8_t check) {
  std::vector<std::uint8_t> image = erased_eeprom_image();
  image[0] = magic;
  image[1] = joint;
  image[2] = baud_code;
  image[3] = check;
  return image;
}

std::vector<std::uint8_t> joint_eeprom_image(std::uint8_t joint, std::uint32_t baud,
                                             const std::optional<joint_bus::JointTuning>& tuning,
                                             const joint_bus::JointOptions& options) {
  if (joint < 1 || joint > 7) {
    throw ArmctlError(ErrorKind::invalid_argument,
                      "joint number " + std::to_string(joint) + " is not allowed (use 1..7)");
  }
  std::uint8_t baud_code = 0;
  if (baud == 9600) {
    baud_code = 0;
  } else if (baud == 115200) {
    baud_code = 1;
  } else {
    throw ArmctlError(ErrorKind::invalid_argument, "joint firmware baud " + std::to_string(baud) +
                                                       " is not allowed (use 9600 or 115200)");
  }
  if (options.polarity == joint_bus::MotorPolarity::reversed) baud_code |= 2u;
  if (options.legacy_master) baud_code |= 4u;
  const auto check = static_cast<std::uint8_t>(0xFF ^ config_magic ^ joint ^ baud_code);
  std::vector<std::uint8_t> image = raw_eeprom_image(config_magic, joint, baud_code, check);
  if (tuning) {
    const std::size_t a = eeprom_tuning_address;
    image[a] = tuning_magic;
    put_int32(image, a + 1, tuning->max_speed_cps);
    put_int32(image, a + 5, tuning->max_accel_cps2);
    put_int32(image, a + 9, tuning->kp_q8);
    put_int32(image, a + 13, tuning->ki_q8);
    put_int32(image, a + 17, tuning->kd_q8);
    const auto pwm = static_cast<std::uint16_t>(tuning->pwm_max);
    image[a + 21] = static_cast<std::uint8_t>(pwm);
    image[a + 22] = static_cast<std::uint8_t>(pwm >> 8);
    std::uint8_t x = 0xFF;
    for (std::size_t i = 0; i < tuning_size - 1; ++i) x = static_cast<std::uint8_t>(x ^ image[a + i]);
    image[a + tuning_size - 1] = x;
  }
  return image;
}

}  // namespace armctl::joint_avr
