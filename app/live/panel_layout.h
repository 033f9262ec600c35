// Where the live panel goes in a window of a given size (issue 32 item 3: the web page on
// phones, tablets and laptops). On a wide window the panel is docked at the left and the
// picture gives up its width, as the desktop has always done; where the panel would take
// more than three quarters of the window (a phone) it is a drawer over the picture, which
// then keeps the whole width. With touch controls (the web page) a visible button opens and closes it, and
// the page starts with it closed where it would leave the picture a strip.
// All sizes in ImGui's (window) pixels.
#pragma once

namespace invfree::live {

constexpr float kPanelDesignWidth = 390.0f;  // the panel's width at UI scale 1

// A finger's target at UI scale 1 (CSS pixels on the page): the drawer's button, the n_seg
// row and its -/+ buttons. Apple asks for 44 pt and Material for 48 dp; 40 keeps the whole
// panel on an 844-px-high phone screen.
constexpr float kTouchTarget = 40.0f;

struct PanelPlacement {
  float x = 0, y = 0, w = 0, h = 0;  // the panel's ImGui window
  bool drawer = false;               // lies over the picture (which keeps the whole width)
  float reserved = 0;                // width the picture gives up to the panel (0: drawer, closed)
};

// The panel of a window_w x window_h window at `ui_scale`; `open`: shown.
PanelPlacement place_panel(float window_w, float window_h, float ui_scale, bool open);

// Whether a touch page opens with the panel shown: only where, docked, it leaves the picture
// (the window less the panel and the det F panel, `det_f_panel_w` wide) at least 40% of the
// window's width. 1280x720 and 1366x768 (48%, 50%) keep it open; at 1024x600 the picture
// would be 38% (a 390-px strip), and a phone's panel is a drawer: both start closed.
bool panel_starts_open(float window_w, float window_h, float ui_scale, float det_f_panel_w);

}  // namespace invfree::live
