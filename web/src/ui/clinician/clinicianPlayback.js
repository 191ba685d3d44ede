// The clinician view's time base: the frames of the recording (else of the target), stepping,
// and playback at the recording's own frame times. Methods of ClinicianView (mixed into its
// prototype), kept here so that the view itself holds its loading and choosing.

import { frameCount, frameTimes, targetFrameAt } from './clinicianFrames.js';

export const playbackMethods = {

	/** Frames of the time base: the recording's, else the target's. */
	frameCount() {

		return frameCount( this.state );

	},

	times() {

		return frameTimes( this.state );

	},

	/** The target frame shown at the current frame. */
	targetFrameIndex() {

		return targetFrameAt( this.state );

	},

	setFrame( frame ) {

		if ( ! Number.isFinite( frame ) ) return;
		this.state.frame = Math.max( 0, Math.min( this.frameCount() - 1, Math.round( frame ) ) );
		this.render();
		if ( ! this.state.playing ) this.url.write();

	},

	step( delta ) {

		this.pause();
		this.setFrame( this.state.frame + delta );

	},

	togglePlay() {

		if ( this.state.playing ) this.pause();
		else this.play();

	},

	/** Play from the current frame at the recording's own frame times (times the speed). */
	play() {

		const from = this.clock.play( this.times(), this.state.frame, this.state.speed );
		if ( from < 0 ) return;
		this.showPlaying( true );
		this.setFrame( from );

	},

	pause() {

		this.clock.pause( { silent: true } );
		this.showPlaying( false );

	},

	setSpeed( speed ) {

		this.state.speed = speed;
		this.clock.setSpeed( speed );

	},

	showPlaying( playing ) {

		this.state.playing = playing;
		if ( ! this.playButton ) return;
		if ( ! playing ) this.url.write();
		const label = playing ? 'Pause' : 'Play';
		this.playButton.textContent = label;
		this.playButton.setAttribute( 'aria-label', label );

	},

};
