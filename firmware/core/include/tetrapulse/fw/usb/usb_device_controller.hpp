#pragma once
// Hardware seam: what the standard requests (UsbControl) ask of a USB device controller
// (stm32f405: OTG FS). Packets and FIFOs stay in the controller's driver; it reports
// control-transfer events to UsbControl (or UsbEndpointZero) and calls nothing else here.
#include <cstdint>

namespace tetrapulse::fw {

class UsbDeviceController {
 public:
  // SET_ADDRESS, at its setup stage. The address must take effect after the status stage
  // (USB 2.0 §9.4.6): a controller that applies it at once in hardware only after the
  // status stage (STM32 OTG) writes it now, others remember it until status_complete.
  void set_address(uint8_t address) { do_set_address(address); }
  // SET_CONFIGURATION: opens (true) or closes the bulk endpoints of the configuration.
  void set_configured(bool configured) { do_set_configured(configured); }
  // ENDPOINT_HALT of a bulk endpoint (address with bit 7 for IN): set stalls it, clear
  // resumes it with its data toggle back to DATA0 (USB 2.0 §9.4.5).
  void set_endpoint_halt(uint8_t endpoint, bool halted) { do_set_endpoint_halt(endpoint, halted); }

 protected:
  ~UsbDeviceController() = default;

 private:
  virtual void do_set_address(uint8_t address) = 0;
  virtual void do_set_configured(bool configured) = 0;
  virtual void do_set_endpoint_halt(uint8_t endpoint, bool halted) = 0;
};

}  // namespace tetrapulse::fw
