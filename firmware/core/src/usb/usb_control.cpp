#include "tetrapulse/fw/usb/usb_control.hpp"

#include "tetrapulse/protocol/usb_device.hpp"

namespace tetrapulse::fw {

namespace tp = protocol;
namespace req = usb_request;

namespace {

constexpr uint8_t kConfigurationValue = 1;  // the one configuration (usb_descriptors.cpp)
constexpr uint8_t kHaltOut = 1u << 0;
constexpr uint8_t kHaltIn = 1u << 1;

}  // namespace

UsbControl::UsbControl(const tp::UsbDeviceParams& params, const char* serial, UsbDeviceController& controller,
                       uint8_t* buffer, size_t capacity)
    : params_(params), serial_(serial), controller_(controller), buffer_(buffer), capacity_(capacity) {}

uint8_t UsbControl::interface_count() const { return params_.mode == tp::UsbMode::kApplication ? 2 : 1; }

void UsbControl::set_function(uint8_t number, UsbFunction& function) {
  if (number < interface_count()) functions_[number] = &function;
}

UsbFunction* UsbControl::function_for(const UsbSetup& setup) const {
  if (setup.recipient() != UsbRecipient::kInterface || !configured()) return nullptr;
  const uint16_t number = setup.index;  // wIndex high byte must be 0 for an interface
  return number < interface_count() ? functions_[number] : nullptr;
}

uint8_t UsbControl::endpoint_bit(uint16_t endpoint) const {
  if (params_.mode != tp::UsbMode::kApplication) return 0;
  if (endpoint == params_.bulk_out_address) return kHaltOut;
  if (endpoint == params_.bulk_in_address) return kHaltIn;
  return 0;
}

UsbControlReply UsbControl::send_bytes(const uint8_t* bytes, size_t size) {
  if (size > capacity_) return UsbControlReply::stall();
  for (size_t i = 0; i < size; ++i) buffer_[i] = bytes[i];
  return UsbControlReply::send(buffer_, size);
}

UsbControlReply UsbControl::send_built(const tp::Result<size_t>& built) {
  return built ? UsbControlReply::send(buffer_, *built) : UsbControlReply::stall();
}

UsbControlReply UsbControl::setup(const UsbSetup& setup) {
  if (setup.type() != UsbRequestType::kStandard) {
    UsbFunction* f = function_for(setup);
    return f != nullptr ? f->setup(setup, buffer_, capacity_) : UsbControlReply::stall();
  }
  switch (setup.recipient()) {
    case UsbRecipient::kDevice:
      return standard_device(setup);
    case UsbRecipient::kInterface:
      return standard_interface(setup);
    case UsbRecipient::kEndpoint:
      return standard_endpoint(setup);
    case UsbRecipient::kOther:
      break;
  }
  return UsbControlReply::stall();
}

UsbControlReply UsbControl::standard_device(const UsbSetup& setup) {
  const bool in = setup.device_to_host();
  switch (setup.request) {
    case req::kGetStatus: {
      if (!in || setup.value != 0 || setup.index != 0) break;
      const uint8_t status[2] = {static_cast<uint8_t>(params_.self_powered ? 1 : 0), 0};  // no remote wakeup
      return send_bytes(status, sizeof(status));
    }
    case req::kSetAddress:
      if (in || setup.value > 127 || setup.index != 0 || setup.length != 0 || configured()) break;
      controller_.set_address(static_cast<uint8_t>(setup.value));
      return UsbControlReply::accept();
    case req::kGetDescriptor:
      if (!in) break;
      return descriptor(setup);
    case req::kGetConfiguration: {
      if (!in || setup.value != 0 || setup.index != 0) break;
      return send_bytes(&configuration_, 1);
    }
    case req::kSetConfiguration:
      if (in || setup.index != 0 || setup.length != 0) break;
      if (setup.value != 0 && setup.value != kConfigurationValue) break;
      set_configuration(static_cast<uint8_t>(setup.value));
      return UsbControlReply::accept();
    default:
      break;  // CLEAR/SET_FEATURE: remote wakeup is not offered, test modes are high speed
  }
  return UsbControlReply::stall();
}

UsbControlReply UsbControl::standard_interface(const UsbSetup& setup) {
  if (!configured() || setup.index >= interface_count()) return UsbControlReply::stall();
  const bool in = setup.device_to_host();
  switch (setup.request) {
    case req::kGetStatus: {
      if (!in || setup.value != 0) break;
      const uint8_t status[2] = {0, 0};
      return send_bytes(status, sizeof(status));
    }
    case req::kGetInterface: {
      if (!in || setup.value != 0) break;
      const uint8_t alternate = 0;
      return send_bytes(&alternate, 1);
    }
    case req::kSetInterface:
      // Only alternate setting 0 exists; hosts select it (dfu-util does) and nothing changes.
      if (in || setup.value != 0 || setup.length != 0) break;
      return UsbControlReply::accept();
    default:
      break;
  }
  return UsbControlReply::stall();
}

UsbControlReply UsbControl::standard_endpoint(const UsbSetup& setup) {
  const bool ep0 = (setup.index & 0x7Fu) == 0;
  const uint8_t bit = endpoint_bit(setup.index);
  if (!ep0 && (bit == 0 || !configured())) return UsbControlReply::stall();
  const bool in = setup.device_to_host();
  switch (setup.request) {
    case req::kGetStatus: {
      if (!in || setup.value != 0) break;
      const uint8_t status[2] = {static_cast<uint8_t>((halted_ & bit) != 0 ? 1 : 0), 0};
      return send_bytes(status, sizeof(status));
    }
    case req::kClearFeature:
    case req::kSetFeature: {
      if (in || setup.value != kUsbFeatureEndpointHalt || setup.length != 0) break;
      if (ep0) return UsbControlReply::accept();  // EP0 halts only for one transfer
      const bool halt = setup.request == req::kSetFeature;
      halted_ = static_cast<uint8_t>(halt ? halted_ | bit : halted_ & ~bit);
      controller_.set_endpoint_halt(static_cast<uint8_t>(setup.index), halt);
      return UsbControlReply::accept();
    }
    default:
      break;
  }
  return UsbControlReply::stall();
}

UsbControlReply UsbControl::descriptor(const UsbSetup& setup) {
  const uint8_t type = static_cast<uint8_t>(setup.value >> 8);
  const uint8_t index = static_cast<uint8_t>(setup.value);
  switch (type) {
    case tp::kUsbDescriptorDevice:
      if (index != 0) break;
      return send_built(tp::build_usb_device_descriptor(params_, buffer_, capacity_));
    case tp::kUsbDescriptorConfiguration:
      if (index != 0) break;
      return send_built(tp::build_usb_configuration_descriptor(params_, buffer_, capacity_));
    case tp::kUsbDescriptorString:
      switch (index) {
        case 0:
          return send_built(tp::build_usb_language_descriptor(buffer_, capacity_));
        case tp::kUsbStringManufacturer:
          return send_built(tp::build_usb_string_descriptor(tp::kUsbManufacturerString, buffer_, capacity_));
        case tp::kUsbStringProduct:
          return send_built(tp::build_usb_string_descriptor(tp::kUsbProductString, buffer_, capacity_));
        case tp::kUsbStringSerial:
          return send_built(tp::build_usb_string_descriptor(serial_, buffer_, capacity_));
        case tp::kUsbStringDfuInterface:
          return send_built(tp::build_usb_string_descriptor(tp::kUsbDfuInterfaceString, buffer_, capacity_));
        default:
          break;
      }
      break;
    default:
      break;  // device qualifier, other speed, BOS: a full-speed USB 2.0 device has none
  }
  return UsbControlReply::stall();
}

void UsbControl::set_configuration(uint8_t value) {
  configuration_ = value;
  halted_ = 0;
  controller_.set_configured(value != 0);
  for (UsbFunction* f : functions_) {
    if (f != nullptr) f->bus_reset();
  }
}

bool UsbControl::data_out(const UsbSetup& setup, tp::ByteView data) {
  if (setup.type() == UsbRequestType::kStandard) return false;  // no standard request takes data here
  UsbFunction* f = function_for(setup);
  return f != nullptr && f->data_out(setup, data);
}

void UsbControl::status_complete(const UsbSetup& setup) {
  if (setup.type() == UsbRequestType::kStandard) return;
  UsbFunction* f = function_for(setup);
  if (f != nullptr) f->status_complete(setup);
}

void UsbControl::bus_reset() {
  configuration_ = 0;
  halted_ = 0;
  for (UsbFunction* f : functions_) {
    if (f != nullptr) f->bus_reset();
  }
}

}  // namespace tetrapulse::fw
