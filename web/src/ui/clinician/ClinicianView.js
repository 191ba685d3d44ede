// The clinician view (route `#/clinician`): choose a target (a saved pose today, phoneme targets
// later: see targets.js) and a client's EPG recording, step through the frames or play them at the
// recording's own frame rate, and read the synthetic and the real palatograms side by side, their
// electrode-by-electrode agreement, the EPG indices of the frame and their curves over time.
//
// The URL holds the selection (#/clinician?recording=12&target=pose:3&frame=40, clinicianUrl.js),
// restored on load; a bad value there is said in words. Recordings can be imported by choosing or
// dropping a file (clinicianImport.js), from a child of the clinician's caseload or as a reference.
// Playback starts at a tenth of real time. Keys: left and right arrows step, Home and End jump,
// space plays and pauses.
//
// Recordings are a clinician's (or an admin's): signed out, or signed in with another role, the
// view is a sign-in prompt (SignInPrompt.js); a token the server stops taking (401) turns the
// view into that prompt too.

import { ClinicianData } from './clinicianData.js';
import { clinicianEpgReport, clinicianReport } from './clinicianReport.js';
import { playbackMethods } from './clinicianPlayback.js';
import { clinicianLayout, DEFAULT_SPEED, fillChoices, keyHandler, offers } from './clinicianLayout.js';
import { RecordingImport } from './clinicianImport.js';
import { EmaPlayback } from './EmaPlayback.js';
import { ChildHistory } from './clinicianChild.js';
import { missingChoiceMessage, SelectionUrl } from './clinicianUrl.js';
import { renderClinician } from './clinicianRender.js';
import { PlaybackClock } from './playbackClock.js';
import { TargetPalate3D } from './TargetPalate3D.js';
import { mountForRoles, signedOutPrompt } from '../shared/SignInPrompt.js';
import { View } from '../shared/View.js';
import '../shared/epg.css';
import '../shared/signin.css';

/** Who may use the view: the roles that read EPG recordings. */
export const CLINICIAN_ROLES = Object.freeze( [ 'clinician', 'admin' ] );

export class ClinicianView extends View {

	/**
	 * @param {{ api?: object, data?: ClinicianData, win?: Window }} options the HTTP client (or a
	 *   data source made on one) and the window whose keys, location and frames the view uses
	 */
	constructor( { api, data = null, win } = {} ) {

		super( { api, win } );
		this.data = data ?? new ClinicianData( { api: this.api } );
		this.clock = new PlaybackClock( {
			onFrame: ( frame ) => this.setFrame( frame ),
			onStop: () => this.showPlaying( false ),
			schedule: ( tick ) => this.window.requestAnimationFrame( tick ),
			cancel: ( handle ) => this.window.cancelAnimationFrame( handle ),
		} );
		this.state = { loaded: false, error: null, frame: 0, playing: false, speed: DEFAULT_SPEED, target: null, recording: null, comparison: null, target3d: null };
		this.loadVersion = 0;

	}

	mount( container ) {

		const actions = {
			chooseTarget: ( name ) => this.chooseTarget( name ),
			chooseRecording: ( id ) => this.chooseRecording( id ),
			setSpeed: ( speed ) => this.setSpeed( speed ),
			setFrame: ( frame ) => this.setFrame( frame ),
			step: ( delta ) => this.step( delta ),
			lastFrame: () => this.setFrame( this.frameCount() - 1 ),
			togglePlay: () => this.togglePlay(),
		};
		this.importer = new RecordingImport( { onImported: ( body ) => this.imported( body ), onError: ( error ) => this.failWith( error, { quiet: true } ) } );
		Object.assign( this, clinicianLayout( actions, { importBox: this.importer.element } ) );
		// A child of the caseload: their practice and recordings; Compare opens a recording here.
		this.childHistory = new ChildHistory( { api: this.api, onOpen: ( id ) => this.imported( { recordings: [ { id } ] } ) } );
		this.main.append( this.childHistory.element );
		// A speaker's EMA recording beside the head saying its phones.
		this.ema = new EmaPlayback( { api: this.api, win: this.window } );
		this.main.append( this.ema.element );
		this.debugFields( { clinicianChild: () => this.childHistory.report(), ema: () => this.ema.report() } );
		this.attach( container, this.root );

		this.listen( this.window, 'keydown', keyHandler( actions ) );
		this.url = new SelectionUrl( this.window, {
			selection: () => ( { target: this.state.target?.name, recording: this.state.recording?.id, frame: this.state.frame } ),
			writable: () => ! this.state.playing && this.root.isConnected,
			apply: ( hash ) => this.state.loaded && this.applySelection( hash ),
		} );
		this.observeResize( [ this.main, this.plotCard ], () => this.fit() );
		this.observeResize( [ this.ema.element ], () => this.ema.resize() );
		this.registerDebugFields();
		this.render();
		this.load();
		return this;

	}

	registerDebugFields() {

		this.debugFields( {
			clinician: () => this.report(),
			epg: () => this.epgReport(),
		} );

	}

	/** The choices, then the selection in the URL. */
	async load() {

		try {

			await this.refreshChoices();
			await this.applySelection( this.window.location.hash );
			this.state.loaded = true;

		} catch ( error ) {

			this.failWith( error );

		}

		await this.loadChildren();
		await this.childHistory.load();

	}

	/** The children the import box offers (the caseload, GET /children); without them, reference only. */
	async loadChildren() {

		try {

			const body = await this.api.get( 'children?limit=1000' );
			this.importer.setChildren( body.children );

		} catch ( error ) {

			if ( ! this.failWith( error, { quiet: true } ) ) console.warn( `Glasshead: the import box lists no children: ${ error.message }` );

		}

	}

	/** Choose what the URL's `hash` names; what is not on offer or cannot be right is said, not chosen. */
	async applySelection( hash ) {

		const selection = this.url.read( hash );
		const problems = [ ...selection.problems ];
		for ( const [ slot, select ] of [ [ 'target', this.targetSelect ], [ 'recording', this.recordingSelect ] ] ) {

			const value = selection[ slot ];
			if ( value && ! offers( select, value ) ) problems.push( missingChoiceMessage( slot, value ) );
			const chosen = value && offers( select, value ) ? value : '';
			if ( chosen === ( slot === 'target' ? this.state.target?.name ?? '' : String( this.state.recording?.id ?? '' ) ) ) continue;
			select.value = chosen;
			await ( slot === 'target' ? this.chooseTarget( chosen, { keepFrame: true } ) : this.chooseRecording( chosen, { keepFrame: true } ) );

		}

		if ( selection.frame !== null ) this.setFrame( selection.frame );
		if ( problems.length && ! this.state.error ) this.fail( problems.join( ' ' ), { log: false } );

	}

	/** List what there is to choose from again, keeping what is chosen. */
	async refreshChoices() {

		const choices = await this.data.choices();
		fillChoices( this, choices );
		this.targetSelect.value = this.state.target?.name ?? '';
		this.recordingSelect.value = this.state.recording ? String( this.state.recording.id ) : '';
		this.showStatus( choices.empty ? 'No recordings or saved poses yet: import a recording below, or save a pose in the workbench.' : '' );

	}

	/** After an import: list the recordings again and show the first one imported. */
	async imported( body ) {

		await this.refreshChoices();
		const id = String( body.recordings[ 0 ].id );
		this.recordingSelect.value = id;
		await this.chooseRecording( id );

	}


	chooseTarget( name, options ) {

		return this.choose( 'target', name, 'Computing the target\'s synthetic EPG…', options );

	}

	chooseRecording( id, options ) {

		return this.choose( 'recording', id, 'Loading the recording…', options );

	}

	/** Load the target or recording `value` (none: clear it), then compare and show. */
	async choose( slot, value, status, { keepFrame = false } = {} ) {

		this.pause();
		const version = ++ this.loadVersion;
		if ( ! value ) {

			this.state[ slot ] = null;

		} else {

			this.showStatus( status );
			try {

				const loaded = await ( slot === 'target' ? this.data.target( value ) : this.data.recording( value ) );
				if ( version !== this.loadVersion ) return null;
				this.state[ slot ] = loaded;
				if ( slot === 'target' ) this.showTarget3d( loaded );

			} catch ( error ) {

				return this.failWith( error );

			}

		}

		return this.compareAndRender( version, keepFrame );

	}

	/**
	 * The target's tongue and electrodes in 3D (targets with parameters; one static frame). A
	 * target of many poses (the head saying a recording's phones) leaves the view empty and says so.
	 */
	async showTarget3d( target ) {

		if ( ! target.params ) {

			this.palate3d?.dispose();
			this.palate3d = null;
			this.state.target3d = null;
			this.caption3d.textContent = 'Target on the palate: shown for a target of one pose';
			return;

		}

		try {

			this.palate3d ??= new TargetPalate3D( this.stage3d, { api: this.api } );
			this.caption3d.textContent = `${ target.label }, palate seen from below`;
			this.state.target3d = await this.palate3d.showParams( target.params );

		} catch ( error ) {

			this.caption3d.textContent = `No 3D view: ${ error.message }`;
			console.warn( `Glasshead: ${ error.message }` );

		}

	}

	/** With both a target and a recording: the compare API's agreement and index differences. */
	async compareAndRender( version, keepFrame ) {

		const { target, recording } = this.state;
		this.state.comparison = null;
		if ( target && recording ) {

			this.showStatus( 'Comparing…' );
			try {

				const comparison = await this.data.compare( recording, target );
				if ( version !== this.loadVersion ) return null;
				this.state.comparison = comparison;

			} catch ( error ) {

				return this.failWith( error );

			}

		}

		this.hideError();
		this.showStatus( '' );
		if ( ! keepFrame ) this.state.frame = 0;
		this.state.frame = Math.min( this.state.frame, this.frameCount() - 1 );
		this.render();
		this.url.write();
		return this.state;

	}

	fit() {

		this.plot.resize( Math.max( 320, Math.min( 900, this.plotCard.clientWidth - 22 ) ) );
		this.strip.resize( Math.max( 320, Math.min( 1400, this.stripCard.clientWidth - 22 ) ) );
		this.render();

	}

	render() {

		renderClinician( this, this.state, { count: this.frameCount(), times: this.times(), targetFrame: this.targetFrameIndex() } );

	}

	/** window.glasshead.clinician */
	report() {

		return clinicianReport( this.state, { frames: this.frameCount(), targetFrame: this.targetFrameIndex(), squares: this.palate3d?.electrodes?.contacted ?? null, imported: this.importer.outcome } );

	}

	/** window.glasshead.epg in this view. */
	epgReport() {

		return clinicianEpgReport( this.state, this.targetFrameIndex() );

	}

	showStatus( text ) {

		this.status.textContent = text;

	}

	/** Show `message` as the view's error (and log it, unless it is about what the user gave). */
	fail( message, { log = true } = {} ) {

		this.state.error = message;
		this.error.textContent = message;
		this.error.hidden = false;
		this.showStatus( '' );
		if ( log ) console.error( `Glasshead: ${ message }` );
		return null;

	}

	/**
	 * Show `error`: a 401 (the token is gone) turns the view into "Please sign in" and returns
	 * true; anything else is the view's error, unless `quiet`, and returns false.
	 */
	failWith( error, { quiet = false } = {} ) {

		const prompt = signedOutPrompt( error, { reason: 'to read EPG recordings', win: this.window, className: 'signin-page' } );
		if ( prompt ) {

			this.pause();
			this.loadVersion ++;
			this.state.error = 'Please sign in';
			this.root.replaceChildren( prompt );
			return true;

		}

		if ( ! quiet ) this.fail( error.message );
		return false;

	}

	hideError() {

		this.state.error = null;
		this.error.hidden = true;

	}

	unmount() {

		this.pause();
		this.loadVersion ++;
		this.url.stop();
		super.unmount();

	}

	dispose() {

		this.palate3d?.dispose();
		this.childHistory?.dispose();
		this.ema?.dispose();

	}

}

// Frames, stepping and playback live in clinicianPlayback.js.
Object.assign( ClinicianView.prototype, playbackMethods );

/** Route entry for the view registry: the view for clinicians and admins, else a sign-in prompt. */
export function mountClinicianView( container, { win = globalThis.window } = {} ) {

	return mountForRoles( container, {
		roles: CLINICIAN_ROLES, reason: 'as a clinician to read EPG recordings', title: 'The clinician view', debugName: 'clinician', win,
		mount: ( box ) => new ClinicianView( { win } ).mount( box ),
	} );

}
