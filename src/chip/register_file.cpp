#include "sercon/chip/register_file.hpp"

#include <stdexcept>
#include <string>

namespace sercon::chip {

RegisterFile::RegisterFile(Variant variant) : variant_(variant) {
  for (std::uint8_t a = 0; a < kRegisterCount; ++a) masks_[a] = register_masks(a, variant);
  reset();
}

std::uint16_t RegisterFile::bus_read(std::uint8_t address) const {
  if (address >= kRegisterCount) return 0;
  const std::uint16_t stored = values_[address];
  const std::uint16_t live = read_hooks_[address] ? read_hooks_[address](stored) : stored;
  return static_cast<std::uint16_t>(live & masks_[address].readable);
}

void RegisterFile::bus_write(std::uint8_t address, std::uint16_t value, std::uint16_t enabled) {
  if (address >= kRegisterCount) return;
  const RegisterMasks& m = masks_[address];
  const std::uint16_t before = values_[address];
  value = static_cast<std::uint16_t>(value & enabled);
  const auto writable = static_cast<std::uint16_t>(m.writable & ~locked_[address] & enabled);
  std::uint16_t next = static_cast<std::uint16_t>((before & ~writable) | (value & writable));
  next = static_cast<std::uint16_t>(next & ~(value & m.clearable & ~held_[address]));
  values_[address] = next;
  if (next != before) changed(address);
  for (const WriteHook& hook : write_hooks_[address]) hook(value, before);
}

void RegisterFile::lock(std::uint8_t address, std::uint16_t mask, bool locked) {
  auto& l = locked_.at(address);
  l = static_cast<std::uint16_t>(locked ? (l | mask) : (l & ~mask));
}

void RegisterFile::hold(std::uint8_t address, std::uint16_t mask, bool held) {
  auto& h = held_.at(address);
  h = static_cast<std::uint16_t>(held ? (h | mask) : (h & ~mask));
}

void RegisterFile::on_write(std::uint8_t address, WriteHook hook) {
  write_hooks_.at(address).push_back(std::move(hook));
}

void RegisterFile::on_read(std::uint8_t address, ReadHook hook) {
  if (read_hooks_.at(address)) {
    throw std::logic_error("RegisterFile::on_read: register " + std::to_string(address) +
                           " already has a read hook");
  }
  read_hooks_[address] = std::move(hook);
}

void RegisterFile::on_change(std::function<void(std::uint8_t)> listener) {
  change_listeners_.push_back(std::move(listener));
}

void RegisterFile::on_change_first(std::function<void(std::uint8_t)> listener) {
  change_listeners_.insert(
      change_listeners_.begin() + static_cast<std::ptrdiff_t>(first_listeners_),
      std::move(listener));
  ++first_listeners_;
}

void RegisterFile::reset() {
  resetting_ = true;
  struct Done {
    bool& flag;
    ~Done() { flag = false; }
  } done{resetting_};
  for (std::uint8_t a = 0; a < kRegisterCount; ++a) {
    const std::uint16_t before = values_[a];
    values_[a] = masks_[a].reset;
    locked_[a] = 0;
    held_[a] = 0;
    if (values_[a] != before) changed(a);
  }
}

void RegisterFile::changed(std::uint8_t address) {
  for (const auto& listener : change_listeners_) listener(address);
}

}  // namespace sercon::chip
