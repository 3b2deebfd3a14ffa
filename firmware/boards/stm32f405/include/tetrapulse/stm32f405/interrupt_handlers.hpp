#pragma once
// The interrupt handlers the vector table (src/startup.cpp) names. Each is weak there and
// defined by the driver that owns the peripheral.
extern "C" {
void TIM2_IRQHandler();
void USART1_IRQHandler();
void TIM8_UP_TIM13_IRQHandler();
void CAN1_TX_IRQHandler();
void CAN1_RX0_IRQHandler();
void CAN1_RX1_IRQHandler();
void CAN1_SCE_IRQHandler();
void OTG_FS_IRQHandler();
void SysTick_Handler();
}
