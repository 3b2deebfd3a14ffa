// Board addresses as users type them: each kind parses, prints back the same, and every
// malformed one is refused with a message that names it.
#include <gtest/gtest.h>

#include "tetrapulse/host/board_address.hpp"

namespace tetrapulse::host {
namespace {

TEST(BoardAddress, EachKindParsesAndPrintsBack) {
  for (const char* text : {"usb:0123456789ABCDEF01234567", "can:vcan0:3", "can:can1:254", "serial:/dev/ttyUSB0:115200",
                           "serial:/dev/ttyACM0:921600", "sim:1"}) {
    auto a = parse_board_address(text);
    ASSERT_TRUE(a) << text << ": " << a.error().what();
    EXPECT_EQ(a->text(), text);
  }
  auto serial = parse_board_address("serial:/dev/ttyS1");
  ASSERT_TRUE(serial);
  EXPECT_EQ(serial->baud, 115200u);
  EXPECT_EQ(serial->serial_path, "/dev/ttyS1");
  auto can = parse_can_address("vcan0:17");
  ASSERT_TRUE(can);
  EXPECT_EQ(can->can_interface, "vcan0");
  EXPECT_EQ(can->node, 17);
}

TEST(BoardAddress, MalformedAddressesSayWhatIsWrong) {
  struct Case {
    const char* text;
    const char* error;
  };
  for (const Case& c : {
           Case{"vcan0:3", "vcan0:3: a board is usb:SERIAL, can:IFACE:NODE, serial:PATH[:BAUD] or sim:NODE"},
           Case{"can:vcan0", "can:vcan0: expected IFACE:NODE, e.g. can0:3"},
           Case{"can:vcan0:0", "can:vcan0:0: node '0' is not a CAN node id 1..254"},
           Case{"can:vcan0:255", "can:vcan0:255: node '255' is not a CAN node id 1..254"},
           Case{"can:vcan0:x", "can:vcan0:x: node 'x' is not a CAN node id 1..254"},
           Case{"can:a-very-long-interface-name:3", "can:a-very-long-interface-name:3: 'a-very-long-interface-name' "
                                                    "is not a network interface name"},
           Case{"serial::9600", "serial::9600: expected PATH[:BAUD], e.g. /dev/ttyUSB0:115200"},
           Case{"usb:has space", "usb:has space: a USB serial number is printable text without spaces"},
           Case{"sim:", "sim:: node '' is not a CAN node id 1..254"},
       }) {
    auto a = parse_board_address(c.text);
    ASSERT_FALSE(a) << c.text;
    EXPECT_EQ(a.error().kind, HostErrorKind::kBadInput);
    EXPECT_EQ(a.error().what(), c.error);
  }
}

TEST(BoardAddress, OpeningWhatIsNotThereIsNotFound) {
  auto can = open_link(*parse_board_address("can:tpnosuch0:3"));
  ASSERT_FALSE(can);
  EXPECT_EQ(can.error().kind, HostErrorKind::kNotFound);
  EXPECT_EQ(can.error().what(), "can:tpnosuch0:3: no such network interface");
  auto serial = open_link(*parse_board_address("serial:/dev/tp-nosuch"));
  ASSERT_FALSE(serial);
  EXPECT_EQ(serial.error().kind, HostErrorKind::kNotFound);
}

}  // namespace
}  // namespace tetrapulse::host
