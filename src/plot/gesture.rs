//! The pointer rules of upload mode's canvases: which presses, moves and releases are a tap, a
//! drag, a pinch or a hover, as one state machine per canvas. The page forwards each event's
//! numbers; what the gesture means (a step picked, the map or the time axis moved) is answered
//! here, and natively tested.
//! May import: nothing.

/// A point on the canvas, in the units the page measures it in (canvas pixels for the map, CSS
/// pixels for the plots).
pub type Point = (f64, f64);

/// How a canvas reads drags: the map pans with each move, the plots' time axis from where the
/// drag was grabbed.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Surface {
    /// The track's map: a move of more than [`MAP_SLOP_PX`] pans by that move; a mouse over it
    /// with no button held hovers.
    Map,
    /// A plot's time axis: a drag pans once it went more than [`AXIS_SLOP_PX`] along the axis from
    /// where it was grabbed; no hover.
    Axis,
}

/// The least move (canvas pixels) of one pointer on the map that pans it.
pub const MAP_SLOP_PX: f64 = 0.5;
/// How far (CSS pixels, along the axis) a drag on a plot goes before it pans rather than taps.
pub const AXIS_SLOP_PX: f64 = 3.0;
/// How near (CSS pixels) a hovering mouse must be to a step to pick it.
pub const HOVER_RADIUS_CSS_PX: f64 = 12.0;
/// How near (CSS pixels) a tap must be to a step to pick it.
pub const TAP_RADIUS_CSS_PX: f64 = 24.0;

/// One event the page forwards: `id` is the event's `pointerId`, `at` where it is.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Input {
    /// A pointer pressed.
    Down {
        /// The pointer.
        id: i32,
        /// Where.
        at: Point,
    },
    /// A pointer moved.
    Move {
        /// The pointer.
        id: i32,
        /// Where it is now.
        at: Point,
        /// Whether it is a mouse (a mouse moves with no button held too).
        mouse: bool,
    },
    /// A pointer released.
    Up {
        /// The pointer.
        id: i32,
        /// Where.
        at: Point,
    },
    /// The browser took the pointer (a scroll, say).
    Cancel {
        /// The pointer.
        id: i32,
    },
    /// The wheel turned.
    Wheel {
        /// Over where.
        at: Point,
        /// The wheel event's `deltaY`.
        delta_y: f64,
    },
    /// A double-click.
    DoubleClick,
}

/// What an event means.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Action {
    /// Nothing to do.
    None,
    /// A mouse over the map: pick the step within [`HOVER_RADIUS_CSS_PX`].
    Hover(Point),
    /// A tap: pick the step within [`TAP_RADIUS_CSS_PX`] (on the map) or at that time (plots).
    Tap(Point),
    /// A drag begins here: the view it pans is kept from now on (plots).
    Grab,
    /// A drag.
    Pan {
        /// The previous point on the map, the grabbed one on a plot.
        from: Point,
        /// Where the pointer is now.
        to: Point,
    },
    /// Two pointers, one of them moved.
    Pinch {
        /// Where the moving one was.
        prev: Point,
        /// Where it is now.
        now: Point,
        /// Where the other one stays.
        other: Point,
    },
    /// Zoom about a point.
    Zoom {
        /// The point kept in place.
        at: Point,
        /// The wheel event's `deltaY`.
        delta_y: f64,
    },
    /// Show everything again.
    Reset,
}

/// A drag in progress: where it was grabbed, and whether it moved (then it is no tap).
#[derive(Debug, Clone, Copy, PartialEq)]
struct Drag {
    origin: Point,
    moved: bool,
}

/// The pointers down on one canvas and the drag they make.
#[derive(Debug, Clone)]
pub struct Gesture {
    surface: Surface,
    /// The pointers held, by id, with where each was last.
    pointers: Vec<(i32, Point)>,
    drag: Option<Drag>,
}

impl Gesture {
    /// No pointer down.
    pub fn new(surface: Surface) -> Self {
        Gesture {
            surface,
            pointers: Vec::new(),
            drag: None,
        }
    }

    /// What `input` means, the state updated.
    pub fn event(&mut self, input: Input) -> Action {
        match input {
            Input::Down { id, at } => self.down(id, at),
            Input::Move { id, at, mouse } => self.moved(id, at, mouse),
            Input::Up { id, at } => self.up(id, at),
            Input::Cancel { id } => {
                self.pointers.retain(|p| p.0 != id);
                if self.surface == Surface::Axis {
                    self.drag = None;
                }
                Action::None
            }
            Input::Wheel { at, delta_y } => Action::Zoom { at, delta_y },
            Input::DoubleClick => Action::Reset,
        }
    }

    fn down(&mut self, id: i32, at: Point) -> Action {
        self.pointers.retain(|p| p.0 != id);
        self.pointers.push((id, at));
        // A second pointer down makes a pinch on a plot, never a tap.
        let moved = self.surface == Surface::Axis && self.pointers.len() > 1;
        self.drag = Some(Drag { origin: at, moved });
        Action::Grab
    }

    fn moved(&mut self, id: i32, at: Point, mouse: bool) -> Action {
        let Some(k) = self.pointers.iter().position(|p| p.0 == id) else {
            return match self.surface {
                Surface::Map if mouse => Action::Hover(at),
                _ => Action::None,
            };
        };
        let prev = std::mem::replace(&mut self.pointers[k].1, at);
        if self.pointers.len() == 2 {
            let other = self.pointers[1 - k].1;
            return Action::Pinch {
                prev,
                now: at,
                other,
            };
        }
        match (self.surface, self.drag.as_mut()) {
            (Surface::Map, Some(drag)) if self.pointers.len() == 1 => {
                if libm::hypot(at.0 - prev.0, at.1 - prev.1) <= MAP_SLOP_PX {
                    return Action::None;
                }
                drag.moved = true;
                Action::Pan { from: prev, to: at }
            }
            (Surface::Axis, Some(drag)) => {
                if (at.0 - drag.origin.0).abs() > AXIS_SLOP_PX {
                    drag.moved = true;
                }
                if !drag.moved {
                    return Action::None;
                }
                Action::Pan {
                    from: drag.origin,
                    to: at,
                }
            }
            _ => Action::None,
        }
    }

    fn up(&mut self, id: i32, at: Point) -> Action {
        let held = self.pointers.iter().position(|p| p.0 == id);
        let last = held.map(|k| self.pointers.remove(k).1);
        let still = self.drag.is_some_and(|d| !d.moved);
        match self.surface {
            // The map taps where the pointer was last seen.
            Surface::Map => match last {
                Some(p) if still => Action::Tap(p),
                _ => Action::None,
            },
            Surface::Axis => {
                if still && self.pointers.is_empty() {
                    self.drag = None;
                    return Action::Tap(at);
                }
                // A finger left after a pinch does not start a pan from where it was: the drag
                // goes on from where it is now.
                self.drag = self.pointers.first().map(|p| Drag {
                    origin: p.1,
                    moved: true,
                });
                if self.drag.is_some() {
                    Action::Grab
                } else {
                    Action::None
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn down(id: i32, x: f64, y: f64) -> Input {
        Input::Down { id, at: (x, y) }
    }
    fn mv(id: i32, x: f64, y: f64) -> Input {
        Input::Move {
            id,
            at: (x, y),
            mouse: false,
        }
    }
    fn up(id: i32, x: f64, y: f64) -> Input {
        Input::Up { id, at: (x, y) }
    }

    #[test]
    fn a_tap_picks_where_it_was() {
        for s in [Surface::Map, Surface::Axis] {
            let mut g = Gesture::new(s);
            assert_eq!(g.event(down(1, 10.0, 20.0)), Action::Grab);
            assert_eq!(g.event(up(1, 10.0, 20.0)), Action::Tap((10.0, 20.0)));
        }
        // A small wobble on a plot is still a tap, where the pointer was released.
        let mut g = Gesture::new(Surface::Axis);
        g.event(down(1, 10.0, 0.0));
        assert_eq!(g.event(mv(1, 12.0, 0.0)), Action::None);
        assert_eq!(g.event(up(1, 12.5, 0.0)), Action::Tap((12.5, 0.0)));
    }

    #[test]
    fn a_drag_pans_and_is_no_tap() {
        let mut map = Gesture::new(Surface::Map);
        map.event(down(1, 0.0, 0.0));
        assert_eq!(map.event(mv(1, 0.3, 0.0)), Action::None);
        assert_eq!(
            map.event(mv(1, 5.0, 0.0)),
            Action::Pan {
                from: (0.3, 0.0),
                to: (5.0, 0.0)
            }
        );
        assert_eq!(map.event(up(1, 5.0, 0.0)), Action::None);

        let mut axis = Gesture::new(Surface::Axis);
        axis.event(down(1, 100.0, 0.0));
        assert_eq!(axis.event(mv(1, 103.0, 0.0)), Action::None);
        let pan = Action::Pan {
            from: (100.0, 0.0),
            to: (104.0, 0.0),
        };
        assert_eq!(axis.event(mv(1, 104.0, 0.0)), pan);
        // Once moving, it pans even back within the slop, always from the grab.
        assert_eq!(
            axis.event(mv(1, 101.0, 0.0)),
            Action::Pan {
                from: (100.0, 0.0),
                to: (101.0, 0.0)
            }
        );
        assert_eq!(axis.event(up(1, 101.0, 0.0)), Action::None);
    }

    #[test]
    fn two_pointers_pinch_and_the_finger_left_grabs_anew() {
        let mut g = Gesture::new(Surface::Axis);
        g.event(down(1, 10.0, 0.0));
        g.event(down(2, 50.0, 0.0));
        assert_eq!(
            g.event(mv(2, 60.0, 0.0)),
            Action::Pinch {
                prev: (50.0, 0.0),
                now: (60.0, 0.0),
                other: (10.0, 0.0)
            }
        );
        // Lifting one finger is no tap: the other grabs where it is.
        assert_eq!(g.event(up(1, 10.0, 0.0)), Action::Grab);
        assert_eq!(
            g.event(mv(2, 61.0, 0.0)),
            Action::Pan {
                from: (60.0, 0.0),
                to: (61.0, 0.0)
            }
        );
        assert_eq!(g.event(up(2, 61.0, 0.0)), Action::None);

        let mut map = Gesture::new(Surface::Map);
        map.event(down(1, 0.0, 0.0));
        map.event(down(2, 10.0, 10.0));
        assert!(matches!(map.event(mv(1, 1.0, 1.0)), Action::Pinch { .. }));
    }

    #[test]
    fn the_wheel_zooms_and_a_double_click_resets() {
        let mut g = Gesture::new(Surface::Map);
        assert_eq!(
            g.event(Input::Wheel {
                at: (3.0, 4.0),
                delta_y: -100.0
            }),
            Action::Zoom {
                at: (3.0, 4.0),
                delta_y: -100.0
            }
        );
        assert_eq!(g.event(Input::DoubleClick), Action::Reset);
    }

    #[test]
    fn a_mouse_hovers_the_map_only() {
        let hover = Input::Move {
            id: 1,
            at: (5.0, 6.0),
            mouse: true,
        };
        assert_eq!(
            Gesture::new(Surface::Map).event(hover),
            Action::Hover((5.0, 6.0))
        );
        assert_eq!(Gesture::new(Surface::Axis).event(hover), Action::None);
        assert_eq!(
            Gesture::new(Surface::Map).event(mv(1, 5.0, 6.0)),
            Action::None
        );
    }

    #[test]
    fn cancel_forgets_the_pointer() {
        let mut g = Gesture::new(Surface::Axis);
        g.event(down(1, 10.0, 0.0));
        assert_eq!(g.event(Input::Cancel { id: 1 }), Action::None);
        assert_eq!(g.event(mv(1, 50.0, 0.0)), Action::None);
        assert_eq!(g.event(up(1, 10.0, 0.0)), Action::None);

        let mut map = Gesture::new(Surface::Map);
        map.event(down(1, 10.0, 0.0));
        map.event(Input::Cancel { id: 1 });
        assert_eq!(map.event(up(1, 10.0, 0.0)), Action::None);
    }
}
