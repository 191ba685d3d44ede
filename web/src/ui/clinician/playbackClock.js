// Playback of EPG frames at their own times (a recording's frame rate, times a speed), pure: the
// clock is handed its time source and its scheduler (performance.now and requestAnimationFrame in
// the page; tests pass their own), and tells onFrame which frame shows as time goes by.
//
//   const clock = new PlaybackClock( { onFrame: ( frame ) => view.setFrame( frame ), onStop } );
//   clock.play( times, view.frame, 0.5 );   // half speed from the frame shown
//   clock.pause();

import { frameAtElapsed } from './clinicianFrames.js';

export class PlaybackClock {

	/**
	 * @param {{ onFrame: ( frame: number ) => void, onStop?: () => void, now?: () => number,
	 *   schedule?: ( tick: ( now: number ) => void ) => any, cancel?: ( handle: any ) => void }} options
	 *   `now` and the times `schedule` hands its tick are milliseconds (performance.now()); onFrame
	 *   is called when the frame changes, onStop when playing ends (at the last frame or by pause)
	 */
	constructor( {
		onFrame,
		onStop = () => {},
		now = () => globalThis.performance.now(),
		schedule = ( tick ) => globalThis.requestAnimationFrame( tick ),
		cancel = ( handle ) => globalThis.cancelAnimationFrame( handle ),
	} ) {

		this.onFrame = onFrame;
		this.onStop = onStop;
		this.now = now;
		this.schedule = schedule;
		this.cancel = cancel;
		this.times = null;
		this.frame = - 1;
		this.speed = 1;
		this.playing = false;
		/** Seconds from the first frame at startMs, and the clock time then. */
		this.startElapsed = 0;
		this.startMs = 0;
		this.handle = null;
		this.tick = ( now ) => this.advance( now );

	}

	/**
	 * Play frames at `times` (seconds, one per frame, increasing) from `frame`; from the first
	 * frame when `frame` is the last. Returns the frame playing starts from, or -1 when there is
	 * nothing to play (fewer than two frames).
	 */
	play( times, frame, speed = this.speed ) {

		this.pause( { silent: true } );
		if ( ! times || times.length < 2 ) return - 1;
		const last = times.length - 1;
		const from = frame >= last || frame < 0 ? 0 : Math.round( frame );
		this.times = times;
		this.frame = from;
		this.speed = speed;
		this.startElapsed = times[ from ] - times[ 0 ];
		this.startMs = this.now();
		this.playing = true;
		this.handle = this.schedule( this.tick );
		return from;

	}

	/** Seconds from the first frame at clock time `now` (ms). */
	elapsedAt( now ) {

		return this.startElapsed + ( now - this.startMs ) / 1000 * this.speed;

	}

	/** Change the speed while playing: the time played so far is kept, the rest goes at `speed`. */
	setSpeed( speed ) {

		if ( this.playing ) {

			const now = this.now();
			this.startElapsed = this.elapsedAt( now );
			this.startMs = now;

		}

		this.speed = speed;

	}

	/** One tick of the scheduler: the frame at `now`, and the next tick or the end. */
	advance( now ) {

		if ( ! this.playing ) return;
		const times = this.times;
		const elapsed = this.elapsedAt( now );
		const frame = frameAtElapsed( times, elapsed );
		if ( frame !== this.frame ) {

			this.frame = frame;
			this.onFrame( frame );

		}

		if ( elapsed >= times[ times.length - 1 ] - times[ 0 ] ) this.pause();
		else if ( this.playing ) this.handle = this.schedule( this.tick );

	}

	/** Stop playing (onStop is told unless `silent`). */
	pause( { silent = false } = {} ) {

		if ( this.handle !== null ) this.cancel( this.handle );
		this.handle = null;
		const was = this.playing;
		this.playing = false;
		if ( was && ! silent ) this.onStop();

	}

}
